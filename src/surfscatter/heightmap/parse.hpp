#pragma once
// Small text helpers shared by the native height map readers (GSF, text grids, X3P). Not a public interface.
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace surfscatter::heightmap::parse {

// s without leading and trailing spaces, tabs and carriage returns.
std::string_view trim(std::string_view s);

// Micrometres per unit of a length unit ("m", "mm", "um", "µm", "μm", "nm", "pm"), or nullopt.
std::optional<double> length_unit_in_um(std::string_view unit);

// UTF-16LE text (an even number of bytes; an odd last byte is an Error naming `what`) as UTF-8, up to the first
// NUL character; unpaired surrogates become U+FFFD.
std::string utf16le_to_utf8(std::string_view bytes, const std::string& what);

// The "name = value" lines of a header (GSF's), the first on line `first_line` of `path`: names and values trimmed,
// blank lines skipped. A line without '=' or a name given twice is an Error naming its line (and the first's).
std::map<std::string, std::string> header_fields(std::string_view text, int first_line, const std::string& path);

// The file's contents; Error "<path>: cannot open height map file" if unreadable.
std::string file_bytes(const std::string& path);

}  // namespace surfscatter::heightmap::parse
