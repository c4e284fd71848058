#pragma once
// The options of a height map's preparation (heightmap/prepare.hpp), one spelling for every command that reads a map
// (`surface info | fit`, `brdf --surface`, `validity --surface-file`, `reference kirchhoff`): --outliers,
// --row-alignment, --form, --lambda-s, --lambda-c.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "surfscatter/heightmap/prepare.hpp"

namespace surfscatter::cli {

struct PreparationArgs {
    // Not given: the defaults of heightmap::Preparation.
    std::optional<std::string> outliers, row_alignment, form, lambda_s, lambda_c;
};

// `map` names what the options apply to in the help texts ("the map", "--surface").
void add_preparation_options(CLI::App* cmd, PreparationArgs& args, const std::string& map = "the map");

// The options checked (an Error naming the option and its value).
heightmap::Preparation parse_preparation(const PreparationArgs& args);

// read_height_map(path, spacing_um, height_unit_um) prepared as `args` asks, its outliers reported on stderr (a
// warning when kept ones hold most of the map's pixel-scale roughness).
// `as_read`, if given, gets the map as read (for pictures of what the preparation did).
heightmap::PreparedMap read_prepared_map(const std::string& path, std::optional<double> spacing_um,
                                         std::optional<double> height_unit_um, const PreparationArgs& args,
                                         std::optional<heightmap::HeightMap>* as_read = nullptr);

}  // namespace surfscatter::cli
