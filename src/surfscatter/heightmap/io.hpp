#pragma once
// Height map files. read_height_map() is the one entry point for reading any of them; docs/HEIGHTMAPS.md says
// which reader handles which format and why.
//
// Native readers (this file):
// * GSF (https://gwyddion.net/documentation/user-guide-en/gsf.html): the line "Gwyddion Simple Field 1.0\n",
//   header lines "name = value\n" (XRes and YRes mandatory; XReal, YReal default 1; XOffset, YOffset, XYUnits,
//   ZUnits, Title optional), one to four NUL bytes so that the data start at a multiple of 4, then XRes*YRes
//   little-endian float32 values row by row; NaN values are invalid points (as in Gwyddion). Lengths in files are
//   converted to um from their XYUnits/ZUnits (m, mm, um, nm, pm); a file without units is rejected, since guessing
//   metres or micrometres would silently be wrong by 10^6. Files are written the way Gwyddion writes them, in base
//   SI units (XYUnits = ZUnits = m), invalid points as NaN.
// * Text grids: one row of heights per line (row iy, column ix), separated by commas, semicolons, tabs or spaces;
//   empty lines are skipped; NaN (any case) is an invalid point. Lines starting with '#' are comments, except the
//   header Gwyddion's text export writes: "# Channel: <title>", "# Width: 10.00 µm", "# Height: 7.50 µm",
//   "# Value units: m". Width and Height state the pixel spacing (width / columns, height / rows) to the precision
//   they are printed with, Value units the height unit. Without them the spacing must be given and the heights are
//   in um unless a height unit is given.
// * X3P: x3p.hpp. Everything else: Gwyddion's file modules (gwyddion_file.hpp).
//
// Every problem (missing file, unknown format, no height channel, bad zip or XML, truncated data, inconsistent
// sizes, ragged rows, all points invalid, a given spacing or height unit that contradicts the file) throws
// surfscatter::Error whose message starts with the file name (and line for text grids).
#include <filesystem>
#include <optional>
#include <variant>

#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/line_scan.hpp"

namespace surfscatter::heightmap {

// Reads any height map. `spacing_um` (um) and `height_unit_um` (um per height unit) are needed for a text grid
// that does not state them; for every file that states its own they may be given only if they agree with it
// (within the precision the file states them with), and a contradiction is an Error. Fills map.source.
HeightMap read_height_map(const std::filesystem::path& path, std::optional<double> spacing_um,
                          std::optional<double> height_unit_um = std::nullopt);

// The profile a file holds (an .hfm export, a Dektak OPDx line scan: the files read_height_map refuses as
// profiles), or nullopt for any other file (which read_height_map reads or refuses).
std::optional<LineScan> read_line_scan(const std::filesystem::path& path);

// Any surface file read once: the profile it holds (as read_line_scan) or else its map (as read_height_map), for the
// callers that take either (an areal OPDx file was read twice, once to find it is not a line scan).
std::variant<HeightMap, LineScan> read_surface_file(const std::filesystem::path& path, std::optional<double> spacing_um,
                                                   std::optional<double> height_unit_um = std::nullopt);

HeightMap read_gsf(const std::filesystem::path& path);

void write_gsf(const HeightMap& map, const std::filesystem::path& path);

// Writes .gsf (write_gsf) or .gwy (Gwyddion's native format, gwyddion_file.hpp) by the path's extension.
void write_height_map(const HeightMap& map, const std::filesystem::path& path);
// Throws Error "<what> must name a .gsf or .gwy file, got '<path>'" unless write_height_map can write `path`.
void require_height_map_extension(const std::filesystem::path& path, const std::string& what);

// A text grid, with or without Gwyddion's export header (see above).
HeightMap read_text_grid(const std::filesystem::path& path, std::optional<double> spacing_um,
                         std::optional<double> height_unit_um = std::nullopt);

// True if the file starts with the GSF magic line.
bool is_gsf_file(const std::filesystem::path& path);

}  // namespace surfscatter::heightmap
