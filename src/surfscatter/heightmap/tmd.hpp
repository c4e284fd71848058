#pragma once
// TrueMap / GelSight TMD files (docs/HEIGHTMAPS.md, "TMD layout"): the line "Binary TrueMap Data File v2.0\r\n\0"
// (32 bytes), a NUL-terminated comment, nx and ny (uint32), the lengths and offsets along x and y (float32, mm),
// then nx * ny float32 heights in mm, row by row; NaN is an invalid point. Gwyddion 2.62 has no TMD module.
#include <filesystem>
#include <string_view>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// True if the file's first bytes are TMD's magic line.
bool is_tmd(std::string_view head);

// Every inconsistency (truncated header, sizes that do not match the file's length, non-positive lengths,
// infinite heights) is an Error naming the file.
HeightMap read_tmd(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
