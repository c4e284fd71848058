#include "surfscatter/heightmap/mnt.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <zlib.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/compound_file.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {

// Object classes of a MountainsMap document.
constexpr std::uint32_t kSurfaceClass = 9012;      // a measured surface
constexpr std::uint32_t kMeasurementClass = 9062;  // its grid, heights and height axis
constexpr std::uint32_t kHeightsClass = 9049;      // int32 counts
constexpr std::uint32_t kMaskClass = 9056;         // non-measured points
constexpr std::uint32_t kMaskArrayClass = 9048;    // the mask's bytes
constexpr std::uint8_t kMeasured = 9, kNotMeasured = 22;  // the mask's values
constexpr unsigned char kTextMarker = 0x04;               // before a text entry's UTF-16LE characters
constexpr std::size_t kEntryHeader = 10;                  // uint16 tag, uint64 size

// An entry of the tree: its data and where it is ("0001/02bd/0002"), for messages.
struct Node {
    std::string_view data;
    std::string where;
};

struct Entry {
    std::uint16_t tag;
    Node node;
};

// The entries filling `parent` (tag, size, data), each preceded by its own size (uint64) in an object list.
std::vector<Entry> entries(const std::string& path, const Node& parent, bool prefixed) {
    std::vector<Entry> out;
    const std::string_view d = parent.data;
    std::size_t pos = 0;
    while (pos < d.size()) {
        const std::size_t prefix = prefixed ? 8 : 0;
        if (d.size() - pos < prefix + kEntryHeader)
            fail("{}: MountainsMap document: {} bytes left at byte {} of entry '{}', too few for an entry header", path,
                 d.size() - pos, pos, parent.where);
        const std::uint16_t tag = binary::load_u16(d.data() + pos + prefix);
        const std::uint64_t size = binary::load_u64(d.data() + pos + prefix + 2);
        const std::string where = fmt::format("{}{}{:04x}", parent.where, parent.where.empty() ? "" : "/", tag);
        if (size > d.size() - pos - prefix - kEntryHeader)
            fail("{}: MountainsMap document: entry '{}' states {} bytes, its container has {} left", path, where, size,
                 d.size() - pos - prefix - kEntryHeader);
        if (prefixed && binary::load_u64(d.data() + pos) != size + kEntryHeader)
            fail("{}: MountainsMap document: object '{}' is preceded by the size {}, its entry has {} bytes", path, where,
                 binary::load_u64(d.data() + pos), size + kEntryHeader);
        out.push_back({tag, {d.substr(pos + prefix + kEntryHeader, size), where}});
        pos += prefix + kEntryHeader + size;
    }
    return out;
}

std::optional<Node> find(const std::string& path, const Node& parent, std::uint16_t tag) {
    for (Entry& e : entries(path, parent, false))
        if (e.tag == tag) return std::move(e.node);
    return std::nullopt;
}

Node child(const std::string& path, const Node& parent, std::uint16_t tag, const char* what) {
    auto node = find(path, parent, tag);
    if (!node) fail("{}: MountainsMap document: entry '{}' holds no {} (tag {:04x})", path, parent.where, what, tag);
    return std::move(*node);
}

template <typename T>
T value(const std::string& path, const Node& node, const char* what) {
    if (node.data.size() != sizeof(T))
        fail("{}: MountainsMap document: {} (entry '{}') has {} bytes, expected {}", path, what, node.where,
             node.data.size(), sizeof(T));
    if constexpr (sizeof(T) == 8) return std::bit_cast<T>(binary::load_u64(node.data.data()));
    else return std::bit_cast<T>(binary::load_u32(node.data.data()));
}

std::string text(const std::string& path, const Node& node) {
    if (node.data.empty() || static_cast<unsigned char>(node.data[0]) != kTextMarker)
        fail("{}: MountainsMap document: entry '{}' is not a text (its first byte is not 0x04)", path, node.where);
    return parse::utf16le_to_utf8(node.data.substr(1), fmt::format("{}: MountainsMap document: entry '{}'", path, node.where));
}

std::uint32_t object_class(const std::string& path, const Node& object) {
    return value<std::uint32_t>(path, child(path, child(path, object, 0x0001, "object class"), 0x0001, "class number"),
                                "an object's class number");
}

Node object_body(const std::string& path, const Node& object, std::uint32_t expected, const char* what) {
    const std::uint32_t found = object_class(path, object);
    if (found != expected)
        fail("{}: MountainsMap document: {} (entry '{}') is an object of class {}, expected {}", path, what,
             object.where, found, expected);
    return child(path, object, 0x0002, what);
}

// An array object's elements: the count, then the array's size in bytes (uint64) and its blocks, in any order,
// each the offset and number of its elements (uint64, uint32), its compressed size (uint32) and a zlib stream.
std::string array_elements(const std::string& path, const Node& object, std::uint32_t expected_class,
                           std::uint64_t expected_count, std::size_t element_bytes, const char* what) {
    const Node body = object_body(path, object, expected_class, what);
    const std::uint32_t count = value<std::uint32_t>(path, child(path, body, 0x0001, "element count"), what);
    if (count != expected_count)
        fail("{}: MountainsMap document: {} (entry '{}') has {} elements, the grid needs {}", path, what, body.where,
             count, expected_count);
    const Node array = child(path, body, 0x0002, "array data");
    const std::string_view d = array.data;
    if (d.size() < 8) fail("{}: MountainsMap document: {} (entry '{}') is truncated", path, what, array.where);
    const std::uint64_t total = binary::load_u64(d.data());
    if (total != count * element_bytes)
        fail("{}: MountainsMap document: {} (entry '{}') states {} bytes for {} elements, expected {} bytes each", path,
             what, array.where, total, count, element_bytes);
    std::string out(total, '\0');
    std::vector<std::pair<std::uint64_t, std::uint64_t>> blocks;  // element ranges [first, last)
    for (std::size_t pos = 8; pos < d.size();) {
        if (d.size() - pos < 16)
            fail("{}: MountainsMap document: {} (entry '{}'): block header at byte {} truncated", path, what,
                 array.where, pos);
        const std::uint64_t first = binary::load_u64(d.data() + pos);
        const std::uint32_t n = binary::load_u32(d.data() + pos + 8);
        const std::uint32_t compressed = binary::load_u32(d.data() + pos + 12);
        pos += 16;
        if (first > count || n > count - first || compressed > d.size() - pos)
            fail("{}: MountainsMap document: {} (entry '{}'): block of elements {} + {} ({} compressed bytes) does not "
                 "fit the array of {} elements and {} bytes",
                 path, what, array.where, first, n, compressed, count, d.size());
        uLongf length = static_cast<uLongf>(n * element_bytes);
        const int status = uncompress(reinterpret_cast<Bytef*>(out.data() + first * element_bytes), &length,
                                      reinterpret_cast<const Bytef*>(d.data() + pos), compressed);
        if (status != Z_OK || length != n * element_bytes)
            fail("{}: MountainsMap document: {} (entry '{}'): block of elements {} + {} does not decompress to {} "
                 "bytes (zlib: {})",
                 path, what, array.where, first, n, n * element_bytes, status == Z_OK ? "short" : zError(status));
        blocks.emplace_back(first, first + n);
        pos += compressed;
    }
    std::sort(blocks.begin(), blocks.end());
    std::uint64_t covered = 0;
    for (const auto& [first, last] : blocks) {
        if (first != covered)
            fail("{}: MountainsMap document: {} (entry '{}'): its blocks {} elements {} to {}", path, what,
                 array.where, first < covered ? "overlap at" : "leave out", std::min(first, covered),
                 std::max(first, covered));
        covered = last;
    }
    if (covered != count)
        fail("{}: MountainsMap document: {} (entry '{}'): its blocks hold {} of its {} elements", path, what,
             array.where, covered, count);
    return out;
}

// An axis's scale: the spacing or height per count in `unit`, the origin in `display_unit`.
struct Scale {
    double step_um = 0.0, origin_um = 0.0, unit_um = 0.0;
};

Scale scale(const std::string& path, const Node& node, std::uint32_t index, const char* axis) {
    const std::uint32_t found = value<std::uint32_t>(
        path, child(path, child(path, node, 0xffff, "axis label"), 0x0001, "axis index"), "the axis index");
    if (found != index)
        fail("{}: MountainsMap document: the {} axis (entry '{}') has index {}, expected {}", path, axis, node.where,
             found, index);
    const double step = value<double>(path, child(path, node, 0x0001, "step"), "the axis step");
    const std::string unit = text(path, child(path, node, 0x0002, "unit"));
    const std::string display = text(path, child(path, node, 0x0003, "display unit"));
    const double ratio = value<double>(path, child(path, node, 0x0004, "unit ratio"), "the axis unit ratio");
    const double origin = value<double>(path, child(path, node, 0x0005, "origin"), "the axis origin");
    const auto unit_um = parse::length_unit_in_um(unit), display_um = parse::length_unit_in_um(display);
    if (!unit_um || !display_um)
        fail("{}: MountainsMap document: the {} axis's units '{}' and '{}' (entry '{}') are not both lengths (m, mm, "
             "um, nm or pm)",
             path, axis, printable(unit), printable(display), node.where);
    // Valid length units from here on: named in ASCII ("um" for the micro sign).
    const auto ascii = [](const std::string& u) { return parse::length_unit_in_um(u) == 1.0 ? std::string("um") : u; };
    if (!(std::abs(*display_um / *unit_um - ratio) <= 1e-9 * ratio))
        fail("{}: MountainsMap document: the {} axis states {} {} per {}, the units' names {}", path, axis, ratio,
             ascii(unit), ascii(display), *display_um / *unit_um);
    if (!std::isfinite(step) || !(step > 0.0) || !std::isfinite(origin))
        fail("{}: MountainsMap document: the {} axis's step {} {} and origin {} {} must be finite, the step positive",
             path, axis, step, ascii(unit), origin, ascii(display));
    return {step * *unit_um, origin * *display_um, *unit_um};
}

struct LateralAxis {
    Scale scale;
    std::uint32_t points = 0;
};

LateralAxis lateral_axis(const std::string& path, const Node& node, std::uint32_t index, const char* axis) {
    const Node inner = child(path, node, 0xffff, "axis");
    LateralAxis out{scale(path, child(path, inner, 0xffff, "axis scale"), index, axis),
                    value<std::uint32_t>(path, child(path, inner, 0x0001, "number of points"), "the number of points")};
    const auto first = value<std::uint32_t>(path, child(path, inner, 0x0002, "first index"), "the first index");
    const auto last = value<std::uint32_t>(path, child(path, inner, 0x0003, "last index"), "the last index");
    if (out.points == 0 || last < first || last - first + 1 != out.points)
        fail("{}: MountainsMap document: the {} axis (entry '{}') states {} points from index {} to {}", path, axis,
             node.where, out.points, first, last);
    return out;
}

}  // namespace

bool is_mnt(const std::filesystem::path& path, std::string_view head) {
    if (head.size() < 512 || !is_compound_file(head)) return false;
    const unsigned shift = binary::load_u16(head.data() + 30);  // sector size 2^shift: 512 or 4096
    if (shift != 9 && shift != 12) return false;
    const std::uint64_t offset = (std::uint64_t{binary::load_u32(head.data() + 48)} + 1) << shift;
    std::ifstream in(path, std::ios::binary);
    std::string sector(std::size_t{1} << shift, '\0');
    in.seekg(static_cast<std::streamoff>(offset));
    in.read(sector.data(), static_cast<std::streamsize>(sector.size()));
    const std::string_view name("S\0c\0o\0p\0e\0d\0C\0o\0n\0t\0e\0n\0t\0s\0", 28);  // UTF-16LE
    return in && sector.find(name) != std::string::npos;
}

HeightMap read_mnt(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = parse::file_bytes(path);
    const CompoundFile compound(bytes, path);
    const std::optional<std::string> stream = compound.stream("ScopedContents");
    if (!stream) {
        std::string names;
        for (const std::string& name : compound.stream_names()) names += (names.empty() ? "" : ", ") + printable(name);
        fail("{}: a compound file without a ScopedContents stream (it holds {}): not a MountainsMap document", path,
             names.empty() ? "no stream" : names);
    }
    const std::string_view s = *stream;
    if (s.size() < 8 || binary::load_u64(s.data()) != s.size() - 8)
        fail("{}: MountainsMap document: ScopedContents ({} bytes) does not start with its remaining size", path,
             s.size());

    // The document's objects: main (0001) / contents (02bd) / 0002 / 0001, a list of size-prefixed objects.
    const Node contents = child(path, child(path, Node{s.substr(8), ""}, 0x0001, "document body"), 0x02bd, "contents");
    const Node list = child(path, child(path, contents, 0x0002, "object list"), 0x0001, "object list");
    std::vector<Node> surfaces;
    std::vector<std::uint32_t> classes;
    for (Entry& e : entries(path, list, true)) {
        classes.push_back(object_class(path, e.node));
        if (classes.back() == kSurfaceClass) surfaces.push_back(std::move(e.node));
    }
    if (surfaces.empty()) {
        std::sort(classes.begin(), classes.end());
        classes.erase(std::unique(classes.begin(), classes.end()), classes.end());
        fail("{}: a MountainsMap document without a measured surface (object class {}); its objects are of classes {}",
             path, kSurfaceClass, fmt::join(classes, ", "));
    }

    const Node surface = child(path, surfaces.front(), 0x0002, "surface");
    std::string title;
    if (const auto header = find(path, surface, 0xffff))
        if (const auto t = find(path, *header, 0x0004)) title = text(path, *t);
    const Node measurement = child(path, object_body(path, child(path, surface, 0x0001, "measurement"),
                                                     kMeasurementClass, "the measurement"),
                                   0xffff, "measurement");
    const Node grid = child(path, measurement, 0xffff, "grid");
    const LateralAxis x = lateral_axis(path, child(path, grid, 0x0001, "x axis"), 1, "x");
    const LateralAxis y = lateral_axis(path, child(path, grid, 0x0002, "y axis"), 2, "y");
    const std::size_t nx = x.points, ny = y.points;
    binary::require_grid_size(path, nx, ny, "MountainsMap x and y points");
    std::string channel;
    if (const auto header = find(path, grid, 0xffff))
        if (const auto description = find(path, *header, 0xffff))
            if (const auto name = find(path, *description, 0x0001)) channel = text(path, *name);

    const Node z = child(path, measurement, 0x0002, "height axis");
    const Scale zs = scale(path, child(path, z, 0xffff, "height scale"), 3, "height");
    const auto lowest = value<std::int32_t>(path, child(path, z, 0x0001, "lowest count"), "the lowest count");
    const auto highest = value<std::int32_t>(path, child(path, z, 0x0002, "highest count"), "the highest count");
    const std::string counts =
        array_elements(path, child(path, measurement, 0x0001, "heights"), kHeightsClass, std::uint64_t{nx} * ny, 4,
                       "the heights");

    // The mask: (nx + 2) x (ny + 2) bytes, a border of one point around the grid; absent (class 0) when every point
    // was measured.
    std::vector<std::uint8_t> valid;
    if (const auto mask = find(path, grid, 0x0003); mask && object_class(path, *mask) != 0) {
        const Node body = object_body(path, *mask, kMaskClass, "the mask");
        const auto width = value<std::uint32_t>(path, child(path, body, 0x0001, "mask width"), "the mask width");
        const auto height = value<std::uint32_t>(path, child(path, body, 0x0002, "mask height"), "the mask height");
        if (width != nx || height != ny)
            fail("{}: MountainsMap document: the mask is {} x {} points, the grid {} x {}", path, width, height, nx, ny);
        const std::string m = array_elements(path, child(path, body, 0x0005, "mask array"), kMaskArrayClass,
                                             std::uint64_t{nx + 2} * (ny + 2), 1, "the mask");
        valid.resize(nx * ny);
        for (std::size_t iy = 0; iy < ny; ++iy)
            for (std::size_t ix = 0; ix < nx; ++ix) {
                const auto v = static_cast<std::uint8_t>(m[(iy + 1) * (nx + 2) + ix + 1]);
                if (v != kMeasured && v != kNotMeasured)
                    fail("{}: MountainsMap document: mask value {} at column {}, row {} is neither {} (measured) nor {} "
                         "(not measured)",
                         path, v, ix, iy, kMeasured, kNotMeasured);
                valid[iy * nx + ix] = v == kMeasured;
            }
    }

    std::vector<double> heights(nx * ny, 0.0);
    for (std::size_t i = 0; i < heights.size(); ++i) {
        if (!valid.empty() && !valid[i]) continue;
        const auto count = static_cast<std::int32_t>(binary::load_u32(counts.data() + 4 * i));
        if (count < lowest || count > highest)
            fail("{}: MountainsMap document: count {} at column {}, row {} lies outside the range {} to {} the height "
                 "axis states",
                 path, count, i % nx, i / nx, lowest, highest);
        heights[i] = count * zs.step_um + zs.origin_um;
    }
    HeightMap map(nx, ny, x.scale.step_um, y.scale.step_um, std::move(heights), std::move(valid), path);
    map.offset_x = x.scale.origin_um;
    map.offset_y = y.scale.origin_um;
    map.title = title;
    map.source.format = "Digital Surf MountainsMap document (.mnt)";
    map.source.reader = "native:mnt";
    map.source.channel = channel;
    map.source.height_unit_um = zs.unit_um;
    if (surfaces.size() > 1)
        map.source.warnings.push_back(fmt::format("the document holds {} measured surfaces; read the first, '{}'",
                                                  surfaces.size(), printable(title)));
    return map;
}

}  // namespace surfscatter::heightmap
