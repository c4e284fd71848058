#include "surfscatter/heightmap/x3p.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <pugixml.hpp>
#include <zip.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr double kMetreInUm = 1e6;
// Bounds any allocation to what a real measurement could hold (as for .gsf).
constexpr std::uint64_t kMaxSide = std::uint64_t{1} << 20, kMaxPoints = std::uint64_t{1} << 32;

struct ZipCloser {
    void operator()(zip_t* archive) const { zip_discard(archive); }
};
using Archive = std::unique_ptr<zip_t, ZipCloser>;

Archive open_archive(const std::string& path) {
    int code = 0;
    zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY, &code);
    if (!archive) {
        zip_error_t error;
        zip_error_init_with_code(&error, code);
        const std::string message = zip_error_strerror(&error);
        zip_error_fini(&error);
        fail("{}: not a readable zip archive ({})", path, message);
    }
    return Archive(archive);
}

std::string read_entry(zip_t* archive, const std::string& path, const std::string& name) {
    const zip_int64_t index = zip_name_locate(archive, name.c_str(), 0);
    if (index < 0) fail("{}: the archive has no entry '{}'", path, printable(name));
    zip_stat_t stat;
    if (zip_stat_index(archive, static_cast<zip_uint64_t>(index), 0, &stat) != 0 || !(stat.valid & ZIP_STAT_SIZE))
        fail("{}: cannot read the size of '{}' in the archive", path, printable(name));
    if (stat.size > 8 * kMaxPoints) fail("{}: '{}' is {} bytes, larger than any height map", path, printable(name), stat.size);
    zip_file_t* entry = zip_fopen_index(archive, static_cast<zip_uint64_t>(index), 0);
    if (!entry) fail("{}: cannot open '{}' in the archive ({})", path, printable(name), zip_strerror(archive));
    std::string bytes(static_cast<std::size_t>(stat.size), '\0');
    const zip_int64_t read = bytes.empty() ? 0 : zip_fread(entry, bytes.data(), bytes.size());
    const std::string message = read < 0 ? zip_file_strerror(entry) : "";
    zip_fclose(entry);
    if (read < 0 || static_cast<zip_uint64_t>(read) != stat.size)
        fail("{}: '{}' in the archive is damaged ({})", path, printable(name),
             read < 0 ? message : fmt::format("{} of {} bytes", read, stat.size));
    return bytes;
}

std::string_view local_name(const char* name) {
    const std::string_view full(name);
    const std::size_t colon = full.find(':');
    return colon == std::string_view::npos ? full : full.substr(colon + 1);
}

// Child element by name, ignoring namespace prefixes.
pugi::xml_node child(pugi::xml_node node, std::string_view name) {
    for (pugi::xml_node c : node.children())
        if (c.type() == pugi::node_element && local_name(c.name()) == name) return c;
    return {};
}

pugi::xml_document parse_xml(const std::string& path, const std::string& name, const std::string& text) {
    pugi::xml_document document;
    const pugi::xml_parse_result result = document.load_buffer(text.data(), text.size());
    if (!result)
        fail("{}: '{}' is not well-formed XML ({} at byte {})", path, printable(name), result.description(), result.offset);
    return document;
}

class X3pReader {
public:
    X3pReader(std::string path, std::string main_xml, pugi::xml_node root)
        : path_(std::move(path)), main_xml_(printable(main_xml)), root_(root) {}

    // Text of the element at `elements` below the root; Error if missing and `required`.
    std::string text(std::initializer_list<std::string_view> elements, bool required = true) const {
        pugi::xml_node node = root_;
        std::string where(local_name(root_.name()));
        for (std::string_view e : elements) {
            node = child(node, e);
            where += '/';  // piece by piece: `"/" + std::string` trips g++ 12's false -Wrestrict warning
            where += e;
            if (!node) {
                if (required) fail("{}: {} has no {}", path_, main_xml_, where);
                return {};
            }
        }
        return std::string(parse::trim(node.child_value()));
    }

    double number(std::initializer_list<std::string_view> elements, std::optional<double> fallback) const {
        const std::string value = text(elements, !fallback);
        if (value.empty() && fallback) return *fallback;
        const auto parsed = to_double(value);
        if (!parsed || !std::isfinite(*parsed))
            fail("{}: {}: {} = '{}' is not a finite number", path_, main_xml_, join(elements), printable(value));
        return *parsed;
    }

    std::uint64_t size(std::string_view axis) const {
        const std::string value = text({"Record3", "MatrixDimension", axis});
        const auto parsed = to_double(value);
        if (!parsed || !(*parsed >= 1.0) || *parsed != std::floor(*parsed) || *parsed > static_cast<double>(kMaxSide))
            fail("{}: {}: MatrixDimension/{} = '{}' is not a size between 1 and {}", path_, main_xml_, axis, printable(value),
                 kMaxSide);
        return static_cast<std::uint64_t>(*parsed);
    }

    static std::string join(std::initializer_list<std::string_view> elements) {
        std::string s;
        for (std::string_view e : elements) {
            if (!s.empty()) s += '/';
            s += e;
        }
        return s;
    }

private:
    std::string path_, main_xml_;
    pugi::xml_node root_;
};

// Z values of the binary data entry, as Increment * raw + Offset.
std::vector<double> binary_values(const std::string& path, const std::string& bytes, char type, std::size_t count,
                                  double increment, double offset) {
    const std::size_t width = type == 'I' ? 2 : (type == 'L' || type == 'F') ? 4 : 8;
    if (bytes.size() != count * width)
        fail("{}: the point data hold {} bytes, but {} points of DataType {} need {} (inconsistent sizes)", path,
             bytes.size(), count, type, count * width);
    std::vector<double> values(count);
    for (std::size_t i = 0; i < count; ++i) {
        std::uint64_t word = 0;
        for (std::size_t b = 0; b < width; ++b)
            word |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[i * width + b])) << (8 * b);
        double raw = 0.0;
        switch (type) {
            case 'I': raw = static_cast<std::int16_t>(static_cast<std::uint16_t>(word)); break;
            case 'L': raw = static_cast<std::int32_t>(static_cast<std::uint32_t>(word)); break;
            case 'F': raw = std::bit_cast<float>(static_cast<std::uint32_t>(word)); break;
            default: raw = std::bit_cast<double>(word); break;
        }
        values[i] = increment * raw + offset;
    }
    return values;
}

// Entry names of the data links are relative to main.xml's folder or, in some writers, to the archive root.
std::string resolve_link(zip_t* archive, const std::string& folder, const std::string& link) {
    if (!folder.empty() && zip_name_locate(archive, (folder + link).c_str(), 0) >= 0) return folder + link;
    return link;
}

}  // namespace

std::optional<X3pLayout> x3p_layout(const std::filesystem::path& file) {
    const std::string path = file.string();
    const Archive archive = open_archive(path);
    X3pLayout layout;
    if (zip_name_locate(archive.get(), "main.xml", 0) >= 0) {
        layout.main_xml = "main.xml";
    } else {
        const zip_int64_t entries = zip_get_num_entries(archive.get(), 0);
        for (zip_int64_t i = 0; i < entries; ++i) {
            const char* name = zip_get_name(archive.get(), static_cast<zip_uint64_t>(i), 0);
            if (!name) continue;
            const std::string_view entry(name);
            constexpr std::string_view suffix = "/main.xml";
            if (entry.size() <= suffix.size() || entry.substr(entry.size() - suffix.size()) != suffix) continue;
            if (!layout.main_xml.empty())
                fail("{}: the archive holds several main.xml ('{}', '{}'); which one is the measurement?", path,
                     printable(layout.main_xml), printable(entry));
            layout.main_xml = std::string(entry);
        }
        if (layout.main_xml.empty()) return std::nullopt;
    }
    const std::string xml = read_entry(archive.get(), path, layout.main_xml);
    const pugi::xml_document document = parse_xml(path, layout.main_xml, xml);
    layout.root = std::string(local_name(document.document_element().name()));
    return layout;
}

HeightMap read_x3p(const std::filesystem::path& file) {
    const std::string path = file.string();
    const auto layout = x3p_layout(file);
    if (!layout) fail("{}: a zip archive without main.xml is not an X3P file", path);
    if (layout->root != "ISO5436_2" && layout->root != "ISO5436")
        fail("{}: {}'s root element is <{}>, not <ISO5436_2> (or <ISO5436>): not an X3P file", path,
             printable(layout->main_xml), printable(layout->root));
    const Archive archive = open_archive(path);
    const pugi::xml_document document = parse_xml(path, layout->main_xml, read_entry(archive.get(), path, layout->main_xml));
    const X3pReader xml(path, layout->main_xml, document.document_element());
    const std::string folder = layout->main_xml.substr(0, layout->main_xml.size() - std::string_view("main.xml").size());

    const std::string feature = xml.text({"Record1", "FeatureType"});
    if (feature != "SUR")
        fail("{}: FeatureType {} is not a surface (SUR){}", path, printable(feature),
             feature == "PRF" ? ": profiles are not height maps" : feature == "PCL" ? ": point clouds are not grids" : "");
    for (std::string_view axis : {"CX", "CY"})
        if (const std::string type = xml.text({"Record1", "Axes", axis, "AxisType"}); type != "I")
            fail("{}: axis {} has AxisType {}; only incremental axes (I, a regular grid) are height maps", path, axis,
                 printable(type));
    if (const std::string type = xml.text({"Record1", "Axes", "CZ", "AxisType"}); type != "A")
        fail("{}: axis CZ has AxisType {}, expected A (absolute heights)", path, printable(type));
    const double dx = xml.number({"Record1", "Axes", "CX", "Increment"}, std::nullopt);
    const double dy = xml.number({"Record1", "Axes", "CY", "Increment"}, std::nullopt);
    if (!(dx > 0.0) || !(dy > 0.0))
        fail("{}: axis increments must be positive, got CX {} m, CY {} m", path, dx, dy);
    const double z_increment = xml.number({"Record1", "Axes", "CZ", "Increment"}, 1.0);
    const double z_offset = xml.number({"Record1", "Axes", "CZ", "Offset"}, 0.0);

    const std::uint64_t nx = xml.size("SizeX"), ny = xml.size("SizeY"), nz = xml.size("SizeZ");
    if (nz != 1) fail("{}: SizeZ = {}: several layers are not one height map", path, nz);
    if (nx * ny > kMaxPoints) fail("{}: {} x {} points is larger than any height map this reads", path, nx, ny);
    const auto count = static_cast<std::size_t>(nx * ny);

    std::vector<double> values;
    std::vector<std::uint8_t> valid(count, 1);
    const pugi::xml_node record3 = child(document.document_element(), "Record3");
    const pugi::xml_node list = child(record3, "DataList");
    // Binary data need the type; inline values state it too, and an unknown one is refused there as well.
    const std::string type = xml.text({"Record1", "Axes", "CZ", "DataType"}, !list);
    if (!(list && type.empty()) && type != "I" && type != "L" && type != "F" && type != "D")
        fail("{}: CZ DataType '{}' is not I, L, F or D", path, printable(type));
    if (list) {
        values.reserve(count);
        for (pugi::xml_node datum : list.children()) {
            if (datum.type() != pugi::node_element || local_name(datum.name()) != "Datum") continue;
            if (values.size() == count) fail("{}: DataList holds more than SizeX x SizeY = {} values", path, count);
            // A matrix Datum holds z, or "x;y;z" with the x, y of incremental axes left empty: take the last field.
            const std::string_view content = parse::trim(datum.child_value());
            const std::string_view z = content.substr(content.rfind(';') == std::string_view::npos ? 0 : content.rfind(';') + 1);
            if (parse::trim(z).empty()) {
                valid[values.size()] = 0;
                values.push_back(0.0);
                continue;
            }
            const auto raw = to_double(parse::trim(z));
            if (!raw) fail("{}: DataList value {} '{}' is not a number", path, values.size() + 1, printable(content));
            values.push_back(z_increment * *raw + z_offset);
        }
        if (values.size() != count)
            fail("{}: DataList holds {} values, but SizeX x SizeY = {} (inconsistent sizes)", path, values.size(), count);
    } else {
        const std::string link = xml.text({"Record3", "DataLink", "PointDataLink"});
        values = binary_values(path, read_entry(archive.get(), path, resolve_link(archive.get(), folder, link)),
                               type[0], count, z_increment, z_offset);
        if (const std::string valid_link = xml.text({"Record3", "DataLink", "ValidPointsLink"}, false);
            !valid_link.empty()) {
            const std::string bits = read_entry(archive.get(), path, resolve_link(archive.get(), folder, valid_link));
            if (bits.size() != (count + 7) / 8)
                fail("{}: '{}' holds {} bytes, but {} points need {} (inconsistent sizes)", path, printable(valid_link),
                     bits.size(), count, (count + 7) / 8);
            for (std::size_t i = 0; i < count; ++i)
                if (!(static_cast<unsigned char>(bits[i / 8]) & (1u << (i % 8)))) valid[i] = 0;
        }
    }
    for (std::size_t i = 0; i < count; ++i) {
        if (std::isnan(values[i])) valid[i] = 0;
        values[i] *= kMetreInUm;
    }

    HeightMap map(static_cast<std::size_t>(nx), static_cast<std::size_t>(ny), dx * kMetreInUm, dy * kMetreInUm,
                  std::move(values), std::move(valid), path);
    map.offset_x = xml.number({"Record1", "Axes", "CX", "Offset"}, 0.0) * kMetreInUm;
    map.offset_y = xml.number({"Record1", "Axes", "CY", "Offset"}, 0.0) * kMetreInUm;
    map.title = xml.text({"Record2", "Comment"}, false);
    map.source.format = "OpenGPS X3P (ISO 5436-2)";
    map.source.reader = layout->standard() ? "native:x3p" : fmt::format("native:x3p ({}, root <{}>)", layout->main_xml, layout->root);
    map.source.height_unit_um = kMetreInUm;
    return map;
}

}  // namespace surfscatter::heightmap
