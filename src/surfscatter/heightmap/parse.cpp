#include "surfscatter/heightmap/parse.hpp"

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"

namespace surfscatter::heightmap::parse {

std::string_view trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

std::optional<double> length_unit_in_um(std::string_view unit) {
    if (unit == "m") return 1e6;
    if (unit == "mm") return 1e3;
    if (unit == "um" || unit == "\xc2\xb5m" || unit == "\xce\xbcm") return 1.0;  // micro sign, Greek mu
    if (unit == "nm") return 1e-3;
    if (unit == "pm") return 1e-6;
    return std::nullopt;
}

std::string utf16le_to_utf8(std::string_view bytes, const std::string& what) {
    if (bytes.size() % 2 != 0) fail("{}: UTF-16 text of {} bytes (an odd number)", what, bytes.size());
    const auto unit = [&](std::size_t i) {
        return static_cast<char32_t>(static_cast<unsigned char>(bytes[2 * i]) |
                                     static_cast<unsigned char>(bytes[2 * i + 1]) << 8);
    };
    std::string out;
    const std::size_t units = bytes.size() / 2;
    for (std::size_t i = 0; i < units; ++i) {
        char32_t c = unit(i);
        if (c == 0) break;
        if (c >= 0xd800 && c < 0xdc00 && i + 1 < units && unit(i + 1) >= 0xdc00 && unit(i + 1) < 0xe000)
            c = 0x10000 + ((c - 0xd800) << 10) + (unit(++i) - 0xdc00);
        else if (c >= 0xd800 && c < 0xe000)
            c = 0xfffd;
        if (c < 0x80) {
            out += static_cast<char>(c);
        } else if (c < 0x800) {
            out += static_cast<char>(0xc0 | c >> 6);
            out += static_cast<char>(0x80 | (c & 0x3f));
        } else if (c < 0x10000) {
            out += static_cast<char>(0xe0 | c >> 12);
            out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (c & 0x3f));
        } else {
            out += static_cast<char>(0xf0 | c >> 18);
            out += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
            out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
            out += static_cast<char>(0x80 | (c & 0x3f));
        }
    }
    return out;
}

std::map<std::string, std::string> header_fields(std::string_view text, int first_line, const std::string& path) {
    std::map<std::string, std::string> fields;
    std::map<std::string, int> lines;
    std::size_t line_start = 0;
    for (int line_number = first_line; line_start < text.size(); ++line_number) {
        std::size_t line_end = text.find('\n', line_start);
        if (line_end == std::string_view::npos) line_end = text.size();
        const std::string_view line = trim(text.substr(line_start, line_end - line_start));
        line_start = line_end + 1;
        if (line.empty()) continue;
        const std::size_t equals = line.find('=');
        if (equals == std::string_view::npos)
            fail("{}:{}: header line '{}' is not of the form 'name = value'", path, line_number, printable(line));
        std::string name(trim(line.substr(0, equals)));
        if (const auto [it, first] = lines.emplace(name, line_number); !first)
            fail("{}:{}: header field '{}' is given twice (first at line {})", path, line_number, printable(name),
                 it->second);
        fields.emplace(std::move(name), std::string(trim(line.substr(equals + 1))));
    }
    return fields;
}

std::string file_bytes(const std::string& path) {
    // Bounds what a height map file may hold: the GSF reader's 2^32 float samples.
    constexpr std::uint64_t kMaxHeightMapFileBytes = std::uint64_t{16} << 30;
    return read_input_file(path, "height map file", kMaxHeightMapFileBytes);
}

}  // namespace surfscatter::heightmap::parse
