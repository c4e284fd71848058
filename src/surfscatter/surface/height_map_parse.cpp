#include "surfscatter/surface/height_map_parse.hpp"

#include <charconv>
#include <fstream>
#include <iterator>

#include "surfscatter/core/error.hpp"

namespace surfscatter::surface::parse {

std::string_view trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

std::optional<double> to_double(std::string_view text) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

std::optional<double> length_unit_in_um(std::string_view unit) {
    if (unit == "m") return 1e6;
    if (unit == "mm") return 1e3;
    if (unit == "um" || unit == "\xc2\xb5m" || unit == "\xce\xbcm") return 1.0;  // micro sign, Greek mu
    if (unit == "nm") return 1e-3;
    if (unit == "pm") return 1e-6;
    return std::nullopt;
}

std::string file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("{}: cannot open height map file", path);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail("{}: read error", path);
    return bytes;
}

}  // namespace surfscatter::surface::parse
