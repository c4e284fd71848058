#include "surfscatter/surface/height_map_io.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "surfscatter/core/error.hpp"

namespace surfscatter::surface {

namespace {

constexpr std::string_view kGsfMagic = "Gwyddion Simple Field 1.0\n";
constexpr double kMetreInUm = 1e6;

std::string read_file_bytes(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("{}: cannot open height map file", path.string());
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) fail("{}: read error", path.string());
    return bytes;
}

std::string_view trim(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return {};
    const auto last = s.find_last_not_of(" \t\r");
    return s.substr(first, last - first + 1);
}

// The whole of `text` must be a number (no trailing garbage).
std::optional<double> parse_double(std::string_view text) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

// Micrometres per unit of a GSF length unit string.
double length_unit_in_um(const std::string& path, const std::string& key, const std::string& unit) {
    static const std::map<std::string, double, std::less<>> units = {
        {"m", 1e6}, {"mm", 1e3}, {"um", 1.0}, {"\xc2\xb5m", 1.0}, {"\xce\xbcm", 1.0}, {"nm", 1e-3}};
    const auto it = units.find(unit);
    if (it == units.end()) fail("{}: {} = '{}' is not a length unit (m, mm, um or nm)", path, key, unit);
    return it->second;
}

std::size_t parse_resolution(const std::string& path, const std::map<std::string, std::string>& header,
                             const char* key) {
    const auto it = header.find(key);
    if (it == header.end()) fail("{}: mandatory GSF header field {} is missing", path, key);
    std::size_t value = 0;
    const std::string& text = it->second;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value == 0)
        fail("{}: {} = '{}' is not a positive integer", path, key, text);
    return value;
}

double parse_real(const std::string& path, const std::map<std::string, std::string>& header, const char* key,
                  double fallback) {
    const auto it = header.find(key);
    if (it == header.end()) return fallback;
    const auto value = parse_double(it->second);
    if (!value || !std::isfinite(*value)) fail("{}: {} = '{}' is not a finite number", path, key, it->second);
    return *value;
}

std::string require_unit(const std::string& path, const std::map<std::string, std::string>& header,
                         const char* key) {
    const auto it = header.find(key);
    if (it == header.end())
        fail("{}: GSF header has no {} (needed to know the length unit; Gwyddion writes e.g. '{} = m')", path, key,
             key);
    return it->second;
}

}  // namespace

bool is_gsf_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(kGsfMagic.size(), '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    return in && head == kGsfMagic;
}

HeightMap read_gsf(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = read_file_bytes(file);
    if (bytes.compare(0, kGsfMagic.size(), kGsfMagic) != 0)
        fail("{}: not a Gwyddion Simple Field file (first line is not 'Gwyddion Simple Field 1.0')", path);

    const std::size_t nul = bytes.find('\0', kGsfMagic.size());
    if (nul == std::string::npos) fail("{}: GSF header is not terminated by NUL bytes (file truncated?)", path);
    const std::size_t data_start = nul + 4 - nul % 4;
    for (std::size_t i = nul; i < std::min(data_start, bytes.size()); ++i)
        if (bytes[i] != '\0') fail("{}: GSF header padding at byte {} is not NUL", path, i);

    std::map<std::string, std::string> header;
    const std::string_view text(bytes.data() + kGsfMagic.size(), nul - kGsfMagic.size());
    std::size_t line_start = 0;
    for (int line_number = 2; line_start < text.size(); ++line_number) {
        std::size_t line_end = text.find('\n', line_start);
        if (line_end == std::string_view::npos) line_end = text.size();
        const std::string_view line = trim(text.substr(line_start, line_end - line_start));
        line_start = line_end + 1;
        if (line.empty()) continue;
        const std::size_t equals = line.find('=');
        if (equals == std::string_view::npos)
            fail("{}:{}: GSF header line '{}' is not of the form 'name = value'", path, line_number, line);
        header.emplace(std::string(trim(line.substr(0, equals))), std::string(trim(line.substr(equals + 1))));
    }

    const std::size_t nx = parse_resolution(path, header, "XRes");
    const std::size_t ny = parse_resolution(path, header, "YRes");
    // Bounds the byte count below (no overflow) and any allocation to what a real file could hold.
    constexpr std::size_t kMaxSide = std::size_t{1} << 20;
    if (nx > kMaxSide || ny > kMaxSide || nx * ny > (std::size_t{1} << 32))
        fail("{}: XRes x YRes = {} x {} is larger than any height map this reads (2^32 samples)", path, nx, ny);
    const std::uint64_t expected = static_cast<std::uint64_t>(data_start) +
                                   4ull * static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny);
    if (bytes.size() != expected)
        fail("{}: XRes x YRes = {} x {} needs {} bytes of float32 data after the header, the file has {}{}", path, nx,
             ny, 4ull * nx * ny, bytes.size() > data_start ? bytes.size() - data_start : 0,
             bytes.size() < expected ? " (truncated)" : " (trailing bytes)");

    const double xy_unit = length_unit_in_um(path, "XYUnits", require_unit(path, header, "XYUnits"));
    const double z_unit = length_unit_in_um(path, "ZUnits", require_unit(path, header, "ZUnits"));
    const double x_real = parse_real(path, header, "XReal", 1.0);
    const double y_real = parse_real(path, header, "YReal", 1.0);
    if (!(x_real > 0.0)) fail("{}: XReal = {} must be positive", path, x_real);
    if (!(y_real > 0.0)) fail("{}: YReal = {} must be positive", path, y_real);

    std::vector<double> heights(nx * ny);
    const char* data = bytes.data() + data_start;
    for (std::size_t i = 0; i < heights.size(); ++i) {
        unsigned char b[4];
        std::memcpy(b, data + 4 * i, 4);
        const std::uint32_t word = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                                   static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
        heights[i] = static_cast<double>(std::bit_cast<float>(word)) * z_unit;
    }
    HeightMap map(nx, ny, x_real * xy_unit / static_cast<double>(nx), y_real * xy_unit / static_cast<double>(ny),
                  std::move(heights), path);
    map.offset_x = parse_real(path, header, "XOffset", 0.0) * xy_unit;
    map.offset_y = parse_real(path, header, "YOffset", 0.0) * xy_unit;
    if (const auto it = header.find("Title"); it != header.end()) map.title = it->second;
    return map;
}

void write_gsf(const HeightMap& map, const std::filesystem::path& file) {
    const std::string path = file.string();
    if (map.title.find_first_of(std::string("\n\r\0", 3)) != std::string::npos)
        fail("{}: a GSF title cannot contain line breaks or NUL", path);
    std::string header(kGsfMagic);
    header += fmt::format("XRes = {}\nYRes = {}\n", map.nx(), map.ny());
    // Base SI units like Gwyddion; 17 significant digits so that the spacing survives the round trip.
    header += fmt::format("XReal = {:.17g}\nYReal = {:.17g}\n", map.width() / kMetreInUm, map.height() / kMetreInUm);
    if (map.offset_x != 0.0) header += fmt::format("XOffset = {:.17g}\n", map.offset_x / kMetreInUm);
    if (map.offset_y != 0.0) header += fmt::format("YOffset = {:.17g}\n", map.offset_y / kMetreInUm);
    header += "XYUnits = m\nZUnits = m\n";
    if (!map.title.empty()) header += fmt::format("Title = {}\n", map.title);
    header.append(4 - header.size() % 4, '\0');

    std::string data(4 * map.size(), '\0');
    for (std::size_t i = 0; i < map.size(); ++i) {
        const auto word = std::bit_cast<std::uint32_t>(static_cast<float>(map.heights()[i] / kMetreInUm));
        for (int b = 0; b < 4; ++b) data[4 * i + b] = static_cast<char>((word >> (8 * b)) & 0xffu);
    }
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    if (!out) fail("{}: cannot open for writing", path);
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!out) fail("{}: write error", path);
}

HeightMap read_text_grid(const std::filesystem::path& file, double spacing_um, double height_unit_um) {
    const std::string path = file.string();
    require_valid_spacing(spacing_um, path + ": pixel spacing");
    if (!(std::isfinite(height_unit_um) && height_unit_um > 0.0))
        fail("{}: height unit must be a positive number of um, got {}", path, height_unit_um);
    const std::string bytes = read_file_bytes(file);
    if (bytes.find('\0') != std::string::npos) fail("{}: binary data in a text height grid", path);

    std::vector<double> heights;
    std::size_t nx = 0, ny = 0;
    std::size_t line_start = 0;
    for (int line_number = 1; line_start < bytes.size(); ++line_number) {
        std::size_t line_end = bytes.find('\n', line_start);
        if (line_end == std::string::npos) line_end = bytes.size();
        const std::string_view line = trim(std::string_view(bytes).substr(line_start, line_end - line_start));
        line_start = line_end + 1;
        if (line.empty() || line.front() == '#') continue;

        std::size_t columns = 0, pos = 0;
        while (pos <= line.size()) {
            std::size_t end = line.find_first_of(",; \t", pos);
            if (end == std::string_view::npos) end = line.size();
            const std::string_view field = line.substr(pos, end - pos);
            pos = end + 1;
            // Runs of spaces/tabs separate like one; an empty field between commas is an error.
            if (field.empty() && end < line.size() && (line[end] == ' ' || line[end] == '\t')) continue;
            const auto value = parse_double(field);
            if (!value) fail("{}:{}: column {}: '{}' is not a number", path, line_number, columns + 1, field);
            if (!std::isfinite(*value))
                fail("{}:{}: column {}: height is {} (every height must be finite)", path, line_number,
                     columns + 1, field);
            heights.push_back(*value * height_unit_um);
            ++columns;
        }
        if (ny == 0) nx = columns;
        else if (columns != nx)
            fail("{}:{}: row has {} values, the first row has {} (ragged or truncated grid)", path, line_number,
                 columns, nx);
        ++ny;
    }
    if (ny == 0) fail("{}: no height values found", path);
    return HeightMap(nx, ny, spacing_um, spacing_um, std::move(heights), path);
}

HeightMap read_height_map(const std::filesystem::path& path, std::optional<double> spacing_um,
                          std::optional<double> height_unit_um) {
    if (is_gsf_file(path)) {
        if (spacing_um)
            fail("{}: a pixel spacing was given, but a .gsf file stores its own (XReal/XRes)", path.string());
        if (height_unit_um)
            fail("{}: a height unit was given, but a .gsf file stores its own (ZUnits)", path.string());
        return read_gsf(path);
    }
    if (path.extension() == ".gsf") return read_gsf(path);  // reports the bad magic line
    if (!spacing_um)
        fail("{}: a text height grid does not store its pixel spacing; give it (--spacing, um)", path.string());
    return read_text_grid(path, *spacing_um, height_unit_um.value_or(1.0));
}

}  // namespace surfscatter::surface
