#pragma once
// .hfm profile exports (docs/HEIGHTMAPS.md, "HFM layout"): text, the header lines "X;Y;valid" and
// "[mm];[mm];[1/0]" (the units of x and of the heights), then one "x;height;valid" row per point, x increasing
// uniformly, valid 1 or 0. A profile, not an areal map: read_height_map() refuses it with its figures.
#include <filesystem>
#include <string_view>

#include "surfscatter/heightmap/line_scan.hpp"

namespace surfscatter::heightmap {

// True if the file starts with the line "X;Y;valid".
bool is_hfm(std::string_view head);

// The profile, heights in um; Errors name path:line (bad numbers, units, a non-uniform x, ragged rows).
LineScan read_hfm(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
