#pragma once
// NanoFocus NMS files (µsurf confocal microscopes; docs/HEIGHTMAPS.md, "NMS layout"): a binary header with the
// format name "OM_MS_2.0" at byte 32, the height range zmin, zmax (float64, um) at byte 16, the data offset and
// bytes per height (uint32) at byte 1352, nx, ny (uint32) at 1368 and the spacings dx, dy (float64, nm) at 1376;
// at the data offset nx * ny uint16 heights row by row, zmin + q (zmax - zmin) / 65535, optionally followed by an
// 8-bit intensity image of the same size. Gwyddion 2.62's quesant module claims these files and fails on them.
#include <filesystem>
#include <string_view>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// True if the file's first bytes carry the NMS format name at byte 32.
bool is_nms(std::string_view head);

HeightMap read_nms(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
