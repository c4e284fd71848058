#pragma once
// X3P height maps (ISO 5436-2 / ISO 25178-72, OpenGPS) read natively with libzip and pugixml.
//
// An X3P file is a zip archive holding main.xml (axes, sizes, data links) and the data: bindata/data.bin (the
// Z values, x fastest, little-endian; DataType I = int16, L = int32, F = float32, D = float64; every value is
// Increment * raw + Offset, in metres) and optionally bindata/valid.bin (one bit per point, least significant bit
// first, 1 = valid) - or the values inline as <DataList><Datum>...</Datum></DataList> (an empty Datum is invalid).
// NaN values are invalid points too. X and Y must be incremental axes (AxisType I, a regular grid, Increment in
// metres); FeatureType must be SUR (a surface; PRF profiles and PCL point clouds are refused), SizeZ 1.
//
// Files in the wild differ from the standard in ways Gwyddion 2.62's opengps module refuses: main.xml inside a
// folder of the archive ("sample/main.xml", data links relative to that folder or to the archive root) and the
// root element ISO5436 instead of ISO5436_2; this reader accepts both. The MD5 checksums in main.xml are not
// checked: libzip checks every entry's CRC-32, which catches the same corruption.
#include <filesystem>
#include <optional>
#include <string>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// Where an archive keeps main.xml and what its root element is called (namespace prefix removed).
struct X3pLayout {
    std::string main_xml;  // entry name, e.g. "main.xml" or "sample/main.xml"
    std::string root;      // "ISO5436_2" or "ISO5436"
    // As ISO 5436-2 prescribes (what Gwyddion reads): main.xml at the archive root, root element ISO5436_2.
    bool standard() const { return main_xml == "main.xml" && root == "ISO5436_2"; }
};

// The layout of a zip archive with a main.xml (at the root, or else in exactly one folder); nullopt if the file is
// a zip archive without main.xml. Error if it is not a readable zip archive, main.xml is not XML, or several
// folders hold one.
std::optional<X3pLayout> x3p_layout(const std::filesystem::path& path);

HeightMap read_x3p(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
