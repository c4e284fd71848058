#pragma once
// Digital Surf MountainsMap documents (.mnt; docs/HEIGHTMAPS.md, "MNT layout"): a compound file (compound_file.hpp)
// whose stream ScopedContents is a tree of tag-length-value entries holding the document's objects. The measured
// surface (object class 9012) holds an axis record per direction (spacing or height per count, its unit, the
// origin in a display unit, the number of points or the range of counts), the heights as int32 counts in
// zlib-compressed blocks, and optionally a mask of non-measured points. Derived layers (levelled, form removed) are
// operators Mountains recomputes: they hold no heights, and the map read is the measurement as the instrument gave
// it. Gwyddion 2.62 has no module for the format.
#include <filesystem>
#include <string_view>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// True if the file is a compound file whose first directory sector names a ScopedContents stream (only the header,
// `head`, and that sector are read).
bool is_mnt(const std::filesystem::path& path, std::string_view head);

// The document's (first) measured surface, heights and lengths in um, non-measured points invalid. Everything the
// layout makes checkable is checked, each an Error naming the file and the entry: entry sizes against their
// containers, axis indices and unit ratios against the units' names, the number of counts against the grid, every
// block of the height array (offset, length, decompressed size, no gap or overlap), and the counts against the
// range the height axis states.
HeightMap read_mnt(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
