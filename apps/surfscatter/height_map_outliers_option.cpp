#include "height_map_outliers_option.hpp"

#include <cstdio>

#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/outliers.hpp"

namespace surfscatter::cli {

void add_outliers_option(CLI::App* cmd, std::string& outliers) {
    cmd->add_option("--outliers", outliers,
                    "the map's outliers (points far from their 5 x 5 neighbourhood): keep (default) | fill (each "
                    "replaced by its neighbours' median); docs/HEIGHTMAPS.md \"Outliers\"");
}

heightmap::HeightMap read_height_map_with_outliers(const std::string& path, std::optional<double> spacing_um,
                                                 std::optional<double> height_unit_um, const std::string& outliers) {
    const heightmap::OutlierPolicy policy = heightmap::parse_outlier_policy(outliers, "--outliers");
    heightmap::Outliers found;
    heightmap::HeightMap map =
        heightmap::apply_outlier_policy(heightmap::read_height_map(path, spacing_um, height_unit_um), policy, found);
    if (found.count > 0)
        std::fprintf(stderr, "surfscatter: %s: %s: %s\n", heightmap::kept_and_dominant(found, policy) ? "warning" : "note",
                     path.c_str(), heightmap::describe(found, policy).c_str());
    return map;
}

}  // namespace surfscatter::cli
