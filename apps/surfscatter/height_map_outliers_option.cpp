#include "height_map_outliers_option.hpp"

#include <cstdio>

#include "surfscatter/surface/height_map_io.hpp"
#include "surfscatter/surface/height_map_outliers.hpp"

namespace surfscatter::cli {

void add_outliers_option(CLI::App* cmd, std::string& outliers) {
    cmd->add_option("--outliers", outliers,
                    "the map's outliers (points far from their 5 x 5 neighbourhood): keep (default) | fill (each "
                    "replaced by its neighbours' median); docs/HEIGHTMAPS.md \"Outliers\"");
}

surface::HeightMap read_height_map_with_outliers(const std::string& path, std::optional<double> spacing_um,
                                                 std::optional<double> height_unit_um, const std::string& outliers) {
    const surface::OutlierPolicy policy = surface::parse_outlier_policy(outliers, "--outliers");
    surface::Outliers found;
    surface::HeightMap map =
        surface::apply_outlier_policy(surface::read_height_map(path, spacing_um, height_unit_um), policy, found);
    if (found.count > 0)
        std::fprintf(stderr, "surfscatter: %s: %s: %s\n", surface::kept_and_dominant(found, policy) ? "warning" : "note",
                     path.c_str(), surface::describe(found, policy).c_str());
    return map;
}

}  // namespace surfscatter::cli
