#include "surfscatter/heightmap/io.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/gwyddion_file.hpp"
#include "surfscatter/heightmap/hfm.hpp"
#include "surfscatter/heightmap/mnt.hpp"
#include "surfscatter/heightmap/nms.hpp"
#include "surfscatter/heightmap/opdx.hpp"
#include "surfscatter/heightmap/parse.hpp"
#include "surfscatter/heightmap/tmd.hpp"
#include "surfscatter/heightmap/x3p.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr std::string_view kGsfMagic = "Gwyddion Simple Field 1.0\n";
constexpr double kMetreInUm = 1e6;

// Micrometres per unit of a GSF length unit string.
double gsf_length_unit(const std::string& path, const std::string& key, const std::string& unit) {
    const auto um = parse::length_unit_in_um(unit);
    if (!um) fail("{}: {} = '{}' is not a length unit (m, mm, um, nm or pm)", path, key, printable(unit));
    return *um;
}

std::size_t parse_resolution(const std::string& path, const std::map<std::string, std::string>& header,
                             const char* key) {
    const auto it = header.find(key);
    if (it == header.end()) fail("{}: mandatory GSF header field {} is missing", path, key);
    std::size_t value = 0;
    const std::string& text = it->second;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value == 0)
        fail("{}: {} = '{}' is not a positive integer", path, key, printable(text));
    return value;
}

double parse_real(const std::string& path, const std::map<std::string, std::string>& header, const char* key,
                  double fallback) {
    const auto it = header.find(key);
    if (it == header.end()) return fallback;
    const auto value = to_double(it->second);
    if (!value || !std::isfinite(*value)) fail("{}: {} = '{}' is not a finite number", path, key, printable(it->second));
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
    const std::string bytes = parse::file_bytes(path);
    if (bytes.compare(0, kGsfMagic.size(), kGsfMagic) != 0)
        fail("{}: not a Gwyddion Simple Field file (first line is not 'Gwyddion Simple Field 1.0')", path);

    const std::size_t nul = bytes.find('\0', kGsfMagic.size());
    if (nul == std::string::npos) fail("{}: GSF header is not terminated by NUL bytes (file truncated?)", path);
    const std::size_t data_start = nul + 4 - nul % 4;
    for (std::size_t i = nul; i < std::min(data_start, bytes.size()); ++i)
        if (bytes[i] != '\0') fail("{}: GSF header padding at byte {} is not NUL", path, i);

    const std::map<std::string, std::string> header =
        parse::header_fields(std::string_view(bytes).substr(kGsfMagic.size(), nul - kGsfMagic.size()), 2, path);

    const std::size_t nx = parse_resolution(path, header, "XRes");
    const std::size_t ny = parse_resolution(path, header, "YRes");
    // Bounds the byte count below (no overflow) and any allocation to what a real file could hold.
    binary::require_grid_size(path, nx, ny, "XRes x YRes");
    const std::uint64_t expected = static_cast<std::uint64_t>(data_start) +
                                   4ull * static_cast<std::uint64_t>(nx) * static_cast<std::uint64_t>(ny);
    if (bytes.size() != expected)
        fail("{}: XRes x YRes = {} x {} needs {} bytes of float32 data after the header, the file has {}{}", path, nx,
             ny, 4ull * nx * ny, bytes.size() > data_start ? bytes.size() - data_start : 0,
             bytes.size() < expected ? " (truncated)" : " (trailing bytes)");

    const double xy_unit = gsf_length_unit(path, "XYUnits", require_unit(path, header, "XYUnits"));
    const double z_unit = gsf_length_unit(path, "ZUnits", require_unit(path, header, "ZUnits"));
    const double x_real = parse_real(path, header, "XReal", 1.0);
    const double y_real = parse_real(path, header, "YReal", 1.0);
    if (!(x_real > 0.0)) fail("{}: XReal = {} must be positive", path, x_real);
    if (!(y_real > 0.0)) fail("{}: YReal = {} must be positive", path, y_real);

    std::vector<double> heights(nx * ny);
    std::vector<std::uint8_t> valid(nx * ny, 1);
    const char* data = bytes.data() + data_start;
    for (std::size_t i = 0; i < heights.size(); ++i) {
        unsigned char b[4];
        std::memcpy(b, data + 4 * i, 4);
        const std::uint32_t word = static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                                   static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24;
        const float value = std::bit_cast<float>(word);
        if (std::isnan(value)) valid[i] = 0;  // GSF's invalid point (Gwyddion masks NaN the same way)
        heights[i] = static_cast<double>(value) * z_unit;
    }
    HeightMap map(nx, ny, x_real * xy_unit / static_cast<double>(nx), y_real * xy_unit / static_cast<double>(ny),
                  std::move(heights), std::move(valid), path);
    map.offset_x = parse_real(path, header, "XOffset", 0.0) * xy_unit;
    map.offset_y = parse_real(path, header, "YOffset", 0.0) * xy_unit;
    if (const auto it = header.find("Title"); it != header.end()) map.title = it->second;
    map.source.format = "Gwyddion Simple Field (.gsf)";
    map.source.reader = "native:gsf";
    map.source.height_unit_um = z_unit;
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
        const float value = map.valid(i) ? static_cast<float>(map.heights()[i] / kMetreInUm)
                                         : std::numeric_limits<float>::quiet_NaN();
        const auto word = std::bit_cast<std::uint32_t>(value);
        for (int b = 0; b < 4; ++b) data[4 * i + b] = static_cast<char>((word >> (8 * b)) & 0xffu);
    }
    write_file_atomically(file, header + data);
}

void require_height_map_extension(const std::filesystem::path& path, const std::string& what) {
    const std::string extension = path.extension().string();
    if (extension != ".gsf" && extension != ".gwy") fail("{} must name a .gsf or .gwy file, got '{}'", what, path.string());
}

void write_height_map(const HeightMap& map, const std::filesystem::path& path) {
    require_height_map_extension(path, "height map output");
    if (path.extension() == ".gwy") write_atomically(path, [&](const std::filesystem::path& tmp) { gwyddion_write_gwy(map, tmp); });
    else write_gsf(map, path);
}


namespace {

// A length a text header states, "10.00 µm": in um, with half a unit of its last printed digit as tolerance.
struct StatedLength {
    double um = 0.0, tolerance_um = 0.0;
};

StatedLength stated_length(const std::string& path, int line, std::string_view key, std::string_view text) {
    const std::size_t space = text.find(' ');
    const std::string_view number = text.substr(0, space);
    const std::string_view unit = space == std::string_view::npos ? "" : parse::trim(text.substr(space + 1));
    const auto value = to_double(number);
    const auto unit_um = parse::length_unit_in_um(unit);
    if (!value || !std::isfinite(*value) || !(*value > 0.0) || !unit_um)
        fail("{}:{}: '# {}: {}' is not a positive length with a unit (m, mm, um, nm or pm)", path, line, key,
             printable(text));
    // Printed digits after the point, less the exponent: "10.00" -> 2, "1.5e-3" -> 4.
    const std::size_t exponent_at = number.find_first_of("eE");
    const std::string_view mantissa = number.substr(0, exponent_at);
    const std::size_t point = mantissa.find('.');
    int decimals = point == std::string_view::npos ? 0 : static_cast<int>(mantissa.size() - point - 1);
    if (exponent_at != std::string_view::npos)
        decimals -= static_cast<int>(to_double(number.substr(exponent_at + 1)).value_or(0.0));
    return {*value * *unit_um, 0.5 * std::pow(10.0, -decimals) * *unit_um};
}

// What Gwyddion's text export header states.
struct TextHeader {
    std::string channel;
    std::optional<StatedLength> width, height;
    std::optional<double> height_unit_um;
    std::string value_units;
};

void read_header_line(const std::string& path, int line_number, std::string_view comment, TextHeader& header) {
    const std::size_t colon = comment.find(':');
    if (colon == std::string_view::npos) return;
    const std::string_view key = parse::trim(comment.substr(0, colon));
    const std::string_view value = parse::trim(comment.substr(colon + 1));
    if (key == "Channel") {
        header.channel = std::string(value);
    } else if (key == "Width") {
        header.width = stated_length(path, line_number, key, value);
    } else if (key == "Height") {
        header.height = stated_length(path, line_number, key, value);
    } else if (key == "Value units") {
        header.value_units = std::string(value);
        header.height_unit_um = parse::length_unit_in_um(value);
        if (!header.height_unit_um)
            fail("{}:{}: '# Value units: {}' is not a length: the channel{} holds no heights", path, line_number,
                 printable(value), header.channel.empty() ? "" : " '" + printable(header.channel) + "'");
    }
}

}  // namespace

HeightMap read_text_grid(const std::filesystem::path& file, std::optional<double> spacing_um,
                         std::optional<double> height_unit_um) {
    const std::string path = file.string();
    if (spacing_um) require_valid_spacing(*spacing_um, path + ": pixel spacing");
    if (height_unit_um && !(std::isfinite(*height_unit_um) && *height_unit_um > 0.0))
        fail("{}: height unit must be a positive number of um, got {}", path, *height_unit_um);
    const std::string bytes = parse::file_bytes(path);
    if (bytes.find('\0') != std::string::npos) fail("{}: binary data in a text height grid", path);

    TextHeader header;
    std::vector<double> heights;
    std::vector<std::uint8_t> valid;
    std::size_t nx = 0, ny = 0;
    std::size_t line_start = 0;
    for (int line_number = 1; line_start < bytes.size(); ++line_number) {
        std::size_t line_end = bytes.find('\n', line_start);
        if (line_end == std::string::npos) line_end = bytes.size();
        const std::string_view line = parse::trim(std::string_view(bytes).substr(line_start, line_end - line_start));
        line_start = line_end + 1;
        if (line.empty()) continue;
        if (line.front() == '#') {
            read_header_line(path, line_number, line.substr(1), header);
            continue;
        }

        std::size_t columns = 0, pos = 0;
        while (pos <= line.size()) {
            std::size_t end = line.find_first_of(",; \t", pos);
            if (end == std::string_view::npos) end = line.size();
            const std::string_view field = line.substr(pos, end - pos);
            pos = end + 1;
            // Runs of spaces/tabs separate like one; an empty field between commas is an error.
            if (field.empty() && end < line.size() && (line[end] == ' ' || line[end] == '\t')) continue;
            const auto value = to_double(field);
            if (!value)
                fail("{}:{}: column {}: '{}' is not a number", path, line_number, columns + 1, printable(field));
            if (std::isinf(*value))
                fail("{}:{}: column {}: height is {} (every height must be finite; NaN marks an invalid point)",
                     path, line_number, columns + 1, printable(field));
            heights.push_back(*value);
            valid.push_back(std::isnan(*value) ? 0 : 1);
            ++columns;
        }
        if (ny == 0) nx = columns;
        else if (columns != nx)
            fail("{}:{}: row has {} values, the first row has {} (ragged or truncated grid)", path, line_number,
                 columns, nx);
        ++ny;
    }
    if (ny == 0) fail("{}: no height values found", path);

    // Pixel spacing: stated by the header (to its printed precision) or given.
    double dx = 0.0, dy = 0.0;
    if (header.width || header.height) {
        if (!header.width || !header.height)
            fail("{}: the header states '# {}:' but not '# {}:'", path, header.width ? "Width" : "Height",
                 header.width ? "Height" : "Width");
        dx = header.width->um / static_cast<double>(nx);
        dy = header.height->um / static_cast<double>(ny);
        if (spacing_um) {
            const double tol_x = header.width->tolerance_um / static_cast<double>(nx) + 1e-9 * dx;
            const double tol_y = header.height->tolerance_um / static_cast<double>(ny) + 1e-9 * dy;
            if (std::abs(*spacing_um - dx) > tol_x || std::abs(*spacing_um - dy) > tol_y)
                fail("{}: --spacing {} um contradicts the header: Width {} um / {} columns = {} um, Height {} um / {} "
                     "rows = {} um",
                     path, *spacing_um, header.width->um, nx, dx, header.height->um, ny, dy);
            dx = dy = *spacing_um;  // agrees, and is given to more digits than the header prints
        }
    } else {
        if (!spacing_um)
            fail("{}: a text height grid does not store its pixel spacing; give it (--spacing, um)", path);
        dx = dy = *spacing_um;
    }

    double unit = height_unit_um.value_or(1.0);
    if (header.height_unit_um) {
        if (height_unit_um && std::abs(*height_unit_um - *header.height_unit_um) > 1e-9 * *header.height_unit_um)
            fail("{}: --height-unit {} um contradicts the header's '# Value units: {}' ({} um)", path,
                 *height_unit_um, header.value_units, *header.height_unit_um);
        unit = *header.height_unit_um;
    }
    for (double& h : heights) h *= unit;

    HeightMap map(nx, ny, dx, dy, std::move(heights), std::move(valid), path);
    const bool gwyddion_export = header.width || header.height_unit_um || !header.channel.empty();
    map.source.format = gwyddion_export ? "Gwyddion text export (text grid with header)" : "text grid";
    map.source.reader = "native:text";
    map.source.channel = header.channel;
    map.source.height_unit_um = header.height_unit_um.value_or(0.0);
    return map;
}

namespace {

constexpr std::string_view kZipMagic = "PK\x03\x04";

std::string file_head(const std::string& path, std::size_t bytes) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("{}: cannot open height map file", path);
    std::string head(bytes, '\0');
    in.read(head.data(), static_cast<std::streamsize>(bytes));
    head.resize(static_cast<std::size_t>(in.gcount()));
    return head;
}

// A file's stated spacing and height unit against what the user gave (text grids reconcile their own).
void reconcile(const HeightMap& map, std::optional<double> spacing_um, std::optional<double> height_unit_um) {
    const std::string& path = map.origin();
    if (spacing_um) {
        require_valid_spacing(*spacing_um, "--spacing");
        if (std::abs(*spacing_um - map.spacing_x()) > 1e-6 * map.spacing_x() ||
            std::abs(*spacing_um - map.spacing_y()) > 1e-6 * map.spacing_y())
            fail("{}: --spacing {} um contradicts the file, which states dx = {} um, dy = {} um ({})", path,
                 *spacing_um, map.spacing_x(), map.spacing_y(), map.source.format);
    }
    if (height_unit_um && std::abs(*height_unit_um - map.source.height_unit_um) > 1e-9 * map.source.height_unit_um)
        fail("{}: --height-unit {} um contradicts the file, which states its heights in units of {} um ({})", path,
             *height_unit_um, map.source.height_unit_um, map.source.format);
}

HeightMap read_x3p_file(const std::string& path, const X3pLayout& layout) {
    // The native reader checks every field it reads; Gwyddion's opengps module lets bad content pass with exit 0 (a
    // zero increment "fixed" to 1 m, a negative or NaN one, an unknown CZ DataType or a non-number in an inline
    // DataList): the native reading comes first, for every X3P file, and its refusal is the error.
    HeightMap native = read_x3p(path);
    if (!layout.standard()) return native;
    // Gwyddion reads standard files (its reader is the one results name); where it refuses one, the native reading
    // stands.
    try {
        return gwyddion_read(path);
    } catch (const Error& gwyddion_error) {
        native.source.warnings.push_back(fmt::format("Gwyddion refused the file ({}); read natively", gwyddion_error.what()));
        return native;
    }
}

}  // namespace

std::optional<LineScan> read_line_scan(const std::filesystem::path& file) {
    require_readable_file(file, "height map file");
    const std::string head = file_head(file.string(), 65536);
    if (is_hfm(head)) return read_hfm(file);
    if (is_opdx(head))
        if (auto data = read_opdx(file); std::holds_alternative<LineScan>(data)) return std::get<LineScan>(std::move(data));
    return std::nullopt;
}

HeightMap read_height_map(const std::filesystem::path& file, std::optional<double> spacing_um,
                          std::optional<double> height_unit_um) {
    auto data = read_surface_file(file, spacing_um, height_unit_um);
    if (const LineScan* scan = std::get_if<LineScan>(&data)) fail("{}", line_scan_refusal(*scan));
    return std::get<HeightMap>(std::move(data));
}

std::variant<HeightMap, LineScan> read_surface_file(const std::filesystem::path& file, std::optional<double> spacing_um,
                                                   std::optional<double> height_unit_um) {
    const std::string path = file.string();
    require_readable_file(file, "height map file");
    const std::string head = file_head(path, 65536);

    std::optional<HeightMap> map;
    // The native formats first: Gwyddion 2.62 lacks them, or its modules claim them and fail (NMS, OPDx profiles).
    if (head.compare(0, kGsfMagic.size(), kGsfMagic) == 0) {
        map = read_gsf(file);
    } else if (is_tmd(head)) {
        map = read_tmd(file);
    } else if (is_opdx(head)) {
        auto data = read_opdx(file);
        if (LineScan* scan = std::get_if<LineScan>(&data)) return std::move(*scan);
        map = std::move(std::get<HeightMap>(data));
    } else if (is_nms(head)) {
        map = read_nms(file);
    } else if (is_hfm(head)) {
        return read_hfm(file);
    } else if (is_mnt(file, head)) {
        map = read_mnt(file);
    } else if (head.compare(0, kZipMagic.size(), kZipMagic) == 0) {
        if (const auto layout = x3p_layout(path)) map = read_x3p_file(path, *layout);
        else map = gwyddion_read(path);  // other zip-based formats (Sensofar, Keyence, NanoObserver, ...)
    } else if (file.extension() == ".gsf") {
        map = read_gsf(file);  // reports the bad magic line
    } else if (!gwyddion_detect(path).empty()) {
        map = gwyddion_read(path);
    } else if (head.find('\0') == std::string::npos) {
        return read_text_grid(file, spacing_um, height_unit_um);
    } else {
        fail("{}: unknown height map format: none of Gwyddion {}'s {} file modules recognises it, and it is not a "
             "GSF, X3P, TMD, OPDx, NMS, HFM, MNT or text grid",
             path, gwyddion_version(), gwyddion_loader_count());
    }
    reconcile(*map, spacing_um, height_unit_um);
    return std::move(*map);
}

}  // namespace surfscatter::heightmap
