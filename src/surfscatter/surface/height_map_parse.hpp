#pragma once
// Small text helpers shared by the native height map readers (GSF, text grids, X3P). Not a public interface.
#include <optional>
#include <string>
#include <string_view>

namespace surfscatter::surface::parse {

// s without leading and trailing spaces, tabs and carriage returns.
std::string_view trim(std::string_view s);

// Micrometres per unit of a length unit ("m", "mm", "um", "µm", "μm", "nm", "pm"), or nullopt.
std::optional<double> length_unit_in_um(std::string_view unit);

// The file's contents; Error "<path>: cannot open height map file" if unreadable.
std::string file_bytes(const std::string& path);

}  // namespace surfscatter::surface::parse
