// Mitsuba's `serialized` shape: one mesh of a .serialized file (Mitsuba's zlib-compressed binary mesh format).
//
// Supported: `filename`, `shape_index` (default 0), `face_normals` (default false; the file's own face-normal flag
// has the same effect), `flip_normals`, `to_world`. File versions 3 and 4 (little endian, single or double
// precision, 32-bit indices), with vertex normals and texture coordinates; the end-of-file dictionary locates mesh
// shape_index. Vertex colours are read past. A mesh without normals gets Mitsuba's smooth vertex normals.
// Format: Mitsuba 3's documentation of the plugin; decompression by zlib (Debian zlib1g-dev).
// Not supported (an error): 64-bit indices (meshes of more than 2^32 vertices).
// Differences: none.
#include <bit>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

#include <zlib.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

constexpr std::uint16_t kFormat = 0x041C;
enum : std::uint32_t {
    kHasNormals = 0x0001,
    kHasTexcoords = 0x0002,
    kHasColors = 0x0008,
    kFaceNormals = 0x0010,
    kSinglePrecision = 0x1000,
    kDoublePrecision = 0x2000,
};

template <typename T>
T load_le(const std::uint8_t* p) {
    static_assert(std::endian::native == std::endian::little, "the serialized reader assumes a little-endian host");
    T value;
    std::memcpy(&value, p, sizeof value);
    return value;
}

// Inflates the zlib stream starting at `data` until it ends.
std::vector<std::uint8_t> inflate_stream(const std::uint8_t* data, std::size_t size, const std::string& path) {
    z_stream z{};
    if (inflateInit(&z) != Z_OK) fail("{}: cannot initialise zlib", path);
    z.next_in = const_cast<Bytef*>(data);
    z.avail_in = static_cast<uInt>(std::min<std::size_t>(size, 0xFFFFFFFFu));
    std::vector<std::uint8_t> out;
    std::uint8_t buffer[1 << 16];
    int status = Z_OK;
    while (status == Z_OK) {
        z.next_out = buffer;
        z.avail_out = sizeof buffer;
        status = inflate(&z, Z_NO_FLUSH);
        if (status != Z_OK && status != Z_STREAM_END) {
            inflateEnd(&z);
            fail("{}: corrupt compressed mesh data (zlib: {})", path, z.msg ? z.msg : "error");
        }
        out.insert(out.end(), buffer, buffer + (sizeof buffer - z.avail_out));
        // A few bytes can inflate to any size (a "zip bomb"): no mesh is larger than a mesh file may be.
        if (out.size() > kMaxMeshFileBytes) {
            inflateEnd(&z);
            fail("{}: compressed mesh data inflates to more than {} bytes", path, kMaxMeshFileBytes);
        }
        if (status == Z_OK && z.avail_in == 0 && z.avail_out != 0) {
            inflateEnd(&z);
            fail("{}: compressed mesh data ends early", path);
        }
    }
    inflateEnd(&z);
    return out;
}

}  // namespace

TriangleMesh load_serialized(const std::filesystem::path& path, int shape_index, bool& face_normals) {
    return parse_serialized(read_input_file(path, "serialized file", kMaxMeshFileBytes), path, shape_index,
                            face_normals);
}

TriangleMesh parse_serialized(std::string_view bytes, const std::string& path, int shape_index, bool& face_normals) {
    const std::span<const std::uint8_t> file(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    if (file.size() < 8) fail("{}: too short for a serialized mesh", path);
    const auto version = load_le<std::uint16_t>(&file[2]);
    if (load_le<std::uint16_t>(&file[0]) != kFormat) fail("{}: not a Mitsuba serialized file", path);
    if (version != 3 && version != 4) fail("{}: unsupported serialized version {} (3 or 4)", path, version);
    // End-of-file dictionary: offsets (uint64 in version 4, uint32 in 3), then the mesh count (uint32).
    const auto count = load_le<std::uint32_t>(&file[file.size() - 4]);
    if (shape_index < 0 || static_cast<std::uint32_t>(shape_index) >= count)
        fail("{}: shape_index {} is out of range (the file holds {} meshes)", path, shape_index, count);
    const std::size_t entry = version == 4 ? 8 : 4;
    if (count > (file.size() - 4) / entry) fail("{}: truncated mesh dictionary", path);
    const std::size_t at = file.size() - 4 - entry * (count - static_cast<std::size_t>(shape_index));
    const std::size_t offset = version == 4 ? load_le<std::uint64_t>(&file[at]) : load_le<std::uint32_t>(&file[at]);
    if (offset >= file.size() - 4 || load_le<std::uint16_t>(&file[offset]) != kFormat)
        fail("{}: bad offset {} for mesh {}", path, offset, shape_index);
    const std::vector<std::uint8_t> data = inflate_stream(&file[offset + 4], file.size() - offset - 4, path);

    std::size_t pos = 0;
    // Every count read from the data is checked against the bytes left before anything is allocated.
    auto need = [&](std::uint64_t items, std::size_t item_bytes) {
        if (items > (data.size() - pos) / item_bytes) fail("{}: mesh {} data ends early", path, shape_index);
    };
    need(1, 4);
    const auto flags = load_le<std::uint32_t>(&data[pos]);
    pos += 4;
    if (version == 4) {
        while (true) {
            need(1, 1);
            if (data[pos++] == 0) break;
        }
    }
    need(1, 16);
    const auto vertex_count = load_le<std::uint64_t>(&data[pos]);
    const auto triangle_count = load_le<std::uint64_t>(&data[pos + 8]);
    pos += 16;
    if (vertex_count > 0xFFFFFFFFull) fail("{}: meshes with 64-bit indices are not supported", path);
    const bool dp = (flags & kDoublePrecision) != 0;
    const std::size_t scalar = dp ? 8 : 4;
    auto read_reals = [&](std::size_t n, auto&& store) {
        need(n, scalar);
        for (std::size_t i = 0; i < n; ++i, pos += scalar)
            store(i, dp ? load_le<double>(&data[pos]) : static_cast<double>(load_le<float>(&data[pos])));
    };
    TriangleMesh m;
    need(3 * vertex_count, scalar);
    m.positions.resize(vertex_count);
    read_reals(3 * vertex_count, [&](std::size_t i, double v) { m.positions[i / 3][static_cast<int>(i % 3)] = v; });
    if (flags & kHasNormals) {
        m.normals.resize(vertex_count);
        read_reals(3 * vertex_count, [&](std::size_t i, double v) { m.normals[i / 3][static_cast<int>(i % 3)] = v; });
        for (Vec3& n : m.normals) n = n.length() > 0 ? normalize(n) : n;
    }
    if (flags & kHasTexcoords) {
        m.uvs.resize(vertex_count);
        read_reals(2 * vertex_count, [&](std::size_t i, double v) { (i % 2 ? m.uvs[i / 2].y : m.uvs[i / 2].x) = v; });
    }
    if (flags & kHasColors) read_reals(3 * vertex_count, [](std::size_t, double) {});
    need(triangle_count, 12);
    m.triangles.resize(triangle_count);
    for (std::size_t t = 0; t < triangle_count; ++t)
        for (std::size_t k = 0; k < 3; ++k, pos += 4) {
            const auto index = load_le<std::uint32_t>(&data[pos]);
            if (index >= vertex_count) fail("{}: mesh {} has a vertex index {} out of range", path, shape_index, index);
            m.triangles[t][k] = index;
        }
    if (m.triangles.empty()) fail("{}: mesh {} has no triangles", path, shape_index);
    face_normals = (flags & kFaceNormals) != 0;
    return m;
}

ShapeGeometry plugins::serialized(Properties& props) {
    const std::filesystem::path file = props.get_file("filename");
    const int shape_index = props.get_int("shape_index", 0);
    bool file_face_normals = false;
    TriangleMesh mesh = load_serialized(file, shape_index, file_face_normals);
    finish_mesh(mesh, props.get_bool("face_normals", false) || file_face_normals, props.get_transform("to_world"),
                props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
