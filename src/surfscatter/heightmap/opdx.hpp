#pragma once
// Bruker Dektak / Wyko Vision OPDx files (docs/HEIGHTMAPS.md, "OPDx layout"): the magic "VCA DATA\x01\x00\x00\x55",
// then a tree of named, typed items (containers, integers, doubles, strings, quantities with units, arrays). The
// item /MetaData/DataKind says what the file holds: "Surface Height" (an areal map: /2D_Data/<channel>/Matrix of
// float32, Dimension1/2Points and Extent, DataScale) or "Surface Profile" (a stylus line scan: /1D_Data/<channel>/
// Array of float64, NumPoints, Extent from the first point to the last, DataScale). Gwyddion 2.62 reads a profile
// as a curve and then finds no image channel.
#include <filesystem>
#include <string_view>
#include <variant>

#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/line_scan.hpp"

namespace surfscatter::heightmap {

// True if the file starts with the OPDx magic.
bool is_opdx(std::string_view head);

// The map or the profile the file holds. NaN heights are invalid points. Every malformed item (unknown type,
// lengths beyond the file or its container, missing or inconsistent sizes, units that are no lengths) is an Error
// naming the file and the item's path.
std::variant<HeightMap, LineScan> read_opdx(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
