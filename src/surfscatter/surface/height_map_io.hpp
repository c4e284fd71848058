#pragma once
// Height map files: Gwyddion Simple Field (.gsf) and plain text grids (CSV or whitespace separated).
//
// GSF (https://gwyddion.net/documentation/user-guide-en/gsf.html): the line "Gwyddion Simple Field 1.0\n", header
// lines "name = value\n" (XRes and YRes mandatory; XReal, YReal default 1; XOffset, YOffset, XYUnits, ZUnits, Title
// optional), one to four NUL bytes so that the data start at a multiple of 4, then XRes*YRes little-endian float32
// values row by row. Lengths in files are converted to um from their XYUnits/ZUnits (m, mm, um, nm); a file without
// units is rejected, since guessing metres or micrometres would silently be wrong by 10^6. Files are written the
// way Gwyddion writes them, in base SI units (XYUnits = ZUnits = m).
//
// Text grids: one row of heights per line (row iy, column ix), separated by commas, semicolons, tabs or spaces;
// empty lines and lines starting with '#' are skipped; heights are in um unless height_unit_um says otherwise; the
// pixel spacing cannot be stored in the file and must be given.
//
// Every problem (missing file, bad magic, truncated data, ragged rows, NaN heights, ...) throws surfscatter::Error
// whose message starts with the file name (and line for text grids).
#include <filesystem>
#include <optional>

#include "surfscatter/surface/height_map.hpp"

namespace surfscatter::surface {

HeightMap read_gsf(const std::filesystem::path& path);

void write_gsf(const HeightMap& map, const std::filesystem::path& path);

HeightMap read_text_grid(const std::filesystem::path& path, double spacing_um, double height_unit_um = 1.0);

// True if the file starts with the GSF magic line.
bool is_gsf_file(const std::filesystem::path& path);

// Reads a .gsf (spacing and height unit must then be empty: the file stores its own) or a text grid (spacing
// required, height unit default 1 um).
HeightMap read_height_map(const std::filesystem::path& path, std::optional<double> spacing_um,
                          std::optional<double> height_unit_um = std::nullopt);

}  // namespace surfscatter::surface
