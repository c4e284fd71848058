// Mitsuba's `ply` shape: a Stanford PLY triangle mesh.
//
// Supported: `filename`, `face_normals` (default false), `flip_normals`, `to_world`. Formats ascii,
// binary_little_endian and binary_big_endian; vertex x y z, optional nx ny nz and texture coordinates (u v, s t or
// texture_u texture_v); faces as vertex_indices / vertex_index lists (polygons are fanned into triangles). A mesh
// without normals gets Mitsuba's angle-weighted smooth vertex normals unless face_normals is set. Other element
// properties (vertex colours, ...) are skipped, as in Mitsuba's surface shading.
// Differences: none.
#include <algorithm>
#include <bit>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

enum class PlyType { i8, u8, i16, u16, i32, u32, f32, f64 };

PlyType ply_type(const std::string& name, const std::filesystem::path& path) {
    if (name == "char" || name == "int8") return PlyType::i8;
    if (name == "uchar" || name == "uint8") return PlyType::u8;
    if (name == "short" || name == "int16") return PlyType::i16;
    if (name == "ushort" || name == "uint16") return PlyType::u16;
    if (name == "int" || name == "int32") return PlyType::i32;
    if (name == "uint" || name == "uint32") return PlyType::u32;
    if (name == "float" || name == "float32") return PlyType::f32;
    if (name == "double" || name == "float64") return PlyType::f64;
    fail("{}: unknown PLY property type '{}'", path.string(), name);
}

enum class PlyEncoding { ascii, little_endian, big_endian };

template <typename T>
double read_binary(std::istream& in, bool swap) {
    char bytes[sizeof(T)];
    in.read(bytes, sizeof bytes);
    if (swap) std::reverse(std::begin(bytes), std::end(bytes));
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return static_cast<double>(value);
}

double read_value(std::istream& in, PlyType type, PlyEncoding encoding) {
    if (encoding == PlyEncoding::ascii) {
        double v;
        in >> v;
        return v;
    }
    const bool swap = (encoding == PlyEncoding::big_endian) == (std::endian::native == std::endian::little);
    switch (type) {
        case PlyType::i8: return read_binary<std::int8_t>(in, swap);
        case PlyType::u8: return read_binary<std::uint8_t>(in, swap);
        case PlyType::i16: return read_binary<std::int16_t>(in, swap);
        case PlyType::u16: return read_binary<std::uint16_t>(in, swap);
        case PlyType::i32: return read_binary<std::int32_t>(in, swap);
        case PlyType::u32: return read_binary<std::uint32_t>(in, swap);
        case PlyType::f32: return read_binary<float>(in, swap);
        case PlyType::f64: return read_binary<double>(in, swap);
    }
    return 0;
}

struct PlyProperty {
    std::string name;
    PlyType type;
    bool is_list = false;
    PlyType count_type = PlyType::u8;
};

struct PlyElement {
    std::string name;
    std::size_t count = 0;
    std::vector<PlyProperty> properties;
};

}  // namespace

TriangleMesh load_ply(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("cannot open PLY file {}", path.string());
    std::string line;
    std::getline(in, line);
    if (line.rfind("ply", 0) != 0) fail("{}: not a PLY file (missing 'ply' magic)", path.string());
    PlyEncoding encoding = PlyEncoding::little_endian;
    std::vector<PlyElement> elements;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream ls(line);
        std::string tag;
        ls >> tag;
        if (tag == "format") {
            std::string format;
            ls >> format;
            if (format == "ascii") encoding = PlyEncoding::ascii;
            else if (format == "binary_big_endian") encoding = PlyEncoding::big_endian;
            else if (format != "binary_little_endian")
                fail("{}: unsupported PLY format '{}' (ascii, binary_little_endian or binary_big_endian)", path.string(),
                     format);
        } else if (tag == "element") {
            PlyElement e;
            ls >> e.name >> e.count;
            elements.push_back(e);
        } else if (tag == "property") {
            if (elements.empty()) fail("{}: PLY property before any element", path.string());
            std::string type;
            ls >> type;
            PlyProperty p;
            if (type == "list") {
                std::string count_type, item_type;
                ls >> count_type >> item_type >> p.name;
                p.is_list = true;
                p.count_type = ply_type(count_type, path);
                p.type = ply_type(item_type, path);
            } else {
                p.type = ply_type(type, path);
                ls >> p.name;
            }
            elements.back().properties.push_back(p);
        } else if (tag == "end_header") {
            break;
        }
    }
    TriangleMesh m;
    for (const PlyElement& e : elements) {
        for (std::size_t i = 0; i < e.count; ++i) {
            Vec3 p, n;
            Vec2 uv;
            bool has_n = false, has_uv = false;
            for (const PlyProperty& prop : e.properties) {
                if (prop.is_list) {
                    const auto count = static_cast<std::size_t>(read_value(in, prop.count_type, encoding));
                    std::vector<std::uint32_t> idx(count);
                    for (auto& x : idx) x = static_cast<std::uint32_t>(read_value(in, prop.type, encoding));
                    if (e.name == "face" && (prop.name == "vertex_indices" || prop.name == "vertex_index"))
                        for (std::size_t k = 1; k + 1 < count; ++k) m.triangles.push_back({idx[0], idx[k], idx[k + 1]});
                    continue;
                }
                const double value = read_value(in, prop.type, encoding);
                if (e.name != "vertex") continue;
                if (prop.name == "x") p.x = value;
                else if (prop.name == "y") p.y = value;
                else if (prop.name == "z") p.z = value;
                else if (prop.name == "nx") { n.x = value; has_n = true; }
                else if (prop.name == "ny") n.y = value;
                else if (prop.name == "nz") n.z = value;
                else if (prop.name == "u" || prop.name == "s" || prop.name == "texture_u") { uv.x = value; has_uv = true; }
                else if (prop.name == "v" || prop.name == "t" || prop.name == "texture_v") uv.y = value;
            }
            if (!in) fail("{}: PLY data ends early in element '{}'", path.string(), e.name);
            if (e.name == "vertex") {
                m.positions.push_back(p);
                if (has_n) m.normals.push_back(normalize(n));
                if (has_uv) m.uvs.push_back(uv);
            }
        }
    }
    if (m.triangles.empty()) fail("PLY file {} has no faces", path.string());
    for (const auto& t : m.triangles)
        for (std::uint32_t index : t)
            if (index >= m.positions.size())
                fail("{}: PLY face index {} out of range ({} vertices)", path.string(), index, m.positions.size());
    if (m.normals.size() != m.positions.size()) m.normals.clear();
    if (m.uvs.size() != m.positions.size()) m.uvs.clear();
    return m;
}

ShapeGeometry plugins::ply(Properties& props) {
    TriangleMesh mesh = load_ply(props.get_file("filename"));
    finish_mesh(mesh, props.get_bool("face_normals", false), props.get_transform("to_world"),
                props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
