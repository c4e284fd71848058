#include "preparation_options.hpp"

#include <cstdio>

#include "command.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/heightmap/io.hpp"

namespace surfscatter::cli {

void add_preparation_options(CLI::App* cmd, PreparationArgs& args, const std::string& map) {
    cmd->add_option("--outliers", args.outliers,
                    map + "'s outliers (points far from their 5 x 5 neighbourhood): keep (default) | fill (each "
                          "replaced by its neighbours' median); docs/HEIGHTMAPS.md \"Outliers\"");
    cmd->add_option("--row-alignment", args.row_alignment,
                    map + "'s row offsets (scanning instruments): auto (default: aligned when significant) | median "
                          "(always) | none; docs/HEIGHTMAPS.md \"Row alignment\"");
    cmd->add_option("--form", args.form,
                    "form removed from " + map + ": none (mean) | plane (default) | poly2 | poly3 | poly4");
    cmd->add_option("--lambda-s", args.lambda_s,
                    "ISO 16610-61 S-filter on " + map + ": nesting index in um (periods shorter are removed) | none "
                    "(default)");
    cmd->add_option("--lambda-c", args.lambda_c,
                    "ISO 16610-61 L-filter on " + map + ": nesting index in um (periods longer are the waviness) | "
                    "none | auto (default: only when the map's longest periods make its rms uncertain); "
                    "docs/HEIGHTMAPS.md \"Preparation\"");
}

heightmap::Preparation parse_preparation(const PreparationArgs& args) {
    heightmap::Preparation how;
    if (args.outliers) how.outliers = heightmap::parse_outlier_policy(*args.outliers, "--outliers");
    if (args.row_alignment) how.rows = heightmap::parse_row_alignment(*args.row_alignment, "--row-alignment");
    if (args.form) how.form = heightmap::parse_form(*args.form, "--form");
    if (args.lambda_s) how.lambda_s_um = heightmap::parse_lambda_s(*args.lambda_s, "--lambda-s");
    if (args.lambda_c) how.lambda_c_um = heightmap::parse_lambda_c(*args.lambda_c, "--lambda-c");
    return how;
}

heightmap::PreparedMap read_prepared_map(const std::string& path, std::optional<double> spacing_um,
                                         std::optional<double> height_unit_um, const PreparationArgs& args,
                                         std::optional<heightmap::HeightMap>* as_read) {
    const heightmap::Preparation how = parse_preparation(args);
    heightmap::HeightMap read = heightmap::read_height_map(path, spacing_um, height_unit_um);
    heightmap::PreparedMap prepared = heightmap::prepare(read, how);
    if (as_read) *as_read = std::move(read);
    const heightmap::Outliers& found = prepared.outliers;
    if (found.count > 0)
        // outliers_note begins "warning: " when the outliers kept dominate; otherwise it is a note.
        print_note("", heightmap::outliers_note(printable_path(path), found, how.outliers));
    return prepared;
}

}  // namespace surfscatter::cli
