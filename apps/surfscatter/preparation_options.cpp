#include "preparation_options.hpp"

#include <cstdio>

#include "surfscatter/heightmap/io.hpp"

namespace surfscatter::cli {

std::string PreparationArgs::first_given() const {
    if (outliers) return "--outliers";
    if (form) return "--form";
    return "";
}

void add_preparation_options(CLI::App* cmd, PreparationArgs& args, const std::string& map) {
    cmd->add_option("--outliers", args.outliers,
                    map + "'s outliers (points far from their 5 x 5 neighbourhood): keep (default) | fill (each "
                          "replaced by its neighbours' median); docs/HEIGHTMAPS.md \"Outliers\"");
    cmd->add_option("--form", args.form,
                    "form removed from " + map + ": none (mean) | plane (default) | poly2 | poly3 | poly4");
}

heightmap::Preparation parse_preparation(const PreparationArgs& args) {
    heightmap::Preparation how;
    if (args.outliers) how.outliers = heightmap::parse_outlier_policy(*args.outliers, "--outliers");
    if (args.form) how.form = heightmap::parse_form(*args.form, "--form");
    return how;
}

heightmap::PreparedMap read_prepared_map(const std::string& path, std::optional<double> spacing_um,
                                         std::optional<double> height_unit_um, const PreparationArgs& args) {
    const heightmap::Preparation how = parse_preparation(args);
    heightmap::PreparedMap prepared =
        heightmap::prepare(heightmap::read_height_map(path, spacing_um, height_unit_um), how);
    const heightmap::Outliers& found = prepared.outliers;
    if (found.count > 0)
        std::fprintf(stderr, "surfscatter: %s: %s: %s\n",
                     heightmap::kept_and_dominant(found, how.outliers) ? "warning" : "note", path.c_str(),
                     heightmap::describe(found, how.outliers).c_str());
    return prepared;
}

}  // namespace surfscatter::cli
