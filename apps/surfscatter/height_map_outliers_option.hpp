#pragma once
// The --outliers option of the commands that read a height map themselves (`surface info | fit`, `reference
// kirchhoff`) and the reading it asks for: the map with its outliers kept or filled (heightmap/outliers.hpp),
// what was found reported on stderr (a warning when kept ones hold most of the map's pixel-scale roughness).
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::cli {

void add_outliers_option(CLI::App* cmd, std::string& outliers);

// read_height_map(path, spacing_um, height_unit_um), then `outliers` ("keep" | "fill", else an Error naming
// --outliers) applied and reported.
heightmap::HeightMap read_height_map_with_outliers(const std::string& path, std::optional<double> spacing_um,
                                                 std::optional<double> height_unit_um, const std::string& outliers);

}  // namespace surfscatter::cli
