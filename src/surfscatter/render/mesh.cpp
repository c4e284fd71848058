#include "surfscatter/render/mesh.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

TriangleMesh make_rectangle() {
    TriangleMesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

TriangleMesh make_disk(int segments) {
    TriangleMesh m;
    m.positions.push_back({0, 0, 0});
    m.normals.push_back({0, 0, 1});
    m.uvs.push_back({0, 0});
    for (int i = 0; i <= segments; ++i) {
        const double phi = kTwoPi * i / segments;
        m.positions.push_back({std::cos(phi), std::sin(phi), 0});
        m.normals.push_back({0, 0, 1});
        m.uvs.push_back({1.0, static_cast<double>(i) / segments});
    }
    for (int i = 0; i < segments; ++i)
        m.triangles.push_back({0, static_cast<std::uint32_t>(i + 1), static_cast<std::uint32_t>(i + 2)});
    return m;
}

TriangleMesh make_cube() {
    TriangleMesh m;
    const Vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const Vec3& n : normals) {
        const Frame f(n);
        const auto base = static_cast<std::uint32_t>(m.positions.size());
        const Vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const Vec2& c : corners) {
            m.positions.push_back(n + f.s * c.x + f.t * c.y);
            m.normals.push_back(n);
            m.uvs.push_back({(c.x + 1) / 2, (c.y + 1) / 2});
        }
        // Counter-clockwise seen from outside (s x t = n).
        m.triangles.push_back({base, base + 1, base + 2});
        m.triangles.push_back({base, base + 2, base + 3});
    }
    return m;
}

namespace {

std::uint32_t obj_index(long index, std::size_t count, const std::filesystem::path& path, int line) {
    const long resolved = index < 0 ? static_cast<long>(count) + index : index - 1;
    if (index == 0 || resolved < 0 || resolved >= static_cast<long>(count))
        fail("{}:{}: OBJ index {} out of range (1..{})", path.string(), line, index, count);
    return static_cast<std::uint32_t>(resolved);
}

}  // namespace

TriangleMesh load_obj(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) fail("cannot open OBJ file {}", path.string());
    std::vector<Vec3> v, vn;
    std::vector<Vec2> vt;
    struct Corner { std::uint32_t v, vt, vn; bool has_vt, has_vn; };
    std::vector<std::array<Corner, 3>> faces;
    std::string text;
    int line = 0;
    while (std::getline(in, text)) {
        ++line;
        std::istringstream ls(text);
        std::string tag;
        if (!(ls >> tag) || tag[0] == '#') continue;
        if (tag == "v" || tag == "vn") {
            Vec3 p;
            if (!(ls >> p.x >> p.y >> p.z)) fail("{}:{}: malformed '{}' line", path.string(), line, tag);
            (tag == "v" ? v : vn).push_back(p);
        } else if (tag == "vt") {
            Vec2 t;
            if (!(ls >> t.x >> t.y)) fail("{}:{}: malformed 'vt' line", path.string(), line);
            vt.push_back(t);
        } else if (tag == "f") {
            std::vector<Corner> corners;
            std::string item;
            while (ls >> item) {
                Corner c{0, 0, 0, false, false};
                long a = 0, b = 0, n = 0;
                if (std::sscanf(item.c_str(), "%ld/%ld/%ld", &a, &b, &n) == 3) {
                    c = {obj_index(a, v.size(), path, line), obj_index(b, vt.size(), path, line),
                         obj_index(n, vn.size(), path, line), true, true};
                } else if (std::sscanf(item.c_str(), "%ld//%ld", &a, &n) == 2) {
                    c = {obj_index(a, v.size(), path, line), 0, obj_index(n, vn.size(), path, line), false, true};
                } else if (std::sscanf(item.c_str(), "%ld/%ld", &a, &b) == 2) {
                    c = {obj_index(a, v.size(), path, line), obj_index(b, vt.size(), path, line), 0, true, false};
                } else if (std::sscanf(item.c_str(), "%ld", &a) == 1) {
                    c = {obj_index(a, v.size(), path, line), 0, 0, false, false};
                } else {
                    fail("{}:{}: malformed face vertex '{}'", path.string(), line, item);
                }
                corners.push_back(c);
            }
            if (corners.size() < 3) fail("{}:{}: a face needs at least 3 vertices", path.string(), line);
            for (std::size_t i = 1; i + 1 < corners.size(); ++i) faces.push_back({corners[0], corners[i], corners[i + 1]});
        }
    }
    if (faces.empty()) fail("OBJ file {} has no faces", path.string());
    // One output vertex per face corner keeps per-corner uv/normal indices exact.
    TriangleMesh m;
    const bool with_uv = std::all_of(faces.begin(), faces.end(), [](const auto& f) { return f[0].has_vt && f[1].has_vt && f[2].has_vt; });
    const bool with_n = std::all_of(faces.begin(), faces.end(), [](const auto& f) { return f[0].has_vn && f[1].has_vn && f[2].has_vn; });
    for (const auto& f : faces) {
        std::array<std::uint32_t, 3> tri{};
        for (int k = 0; k < 3; ++k) {
            tri[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(m.positions.size());
            m.positions.push_back(v[f[static_cast<std::size_t>(k)].v]);
            if (with_uv) m.uvs.push_back(vt[f[static_cast<std::size_t>(k)].vt]);
            if (with_n) m.normals.push_back(normalize(vn[f[static_cast<std::size_t>(k)].vn]));
        }
        m.triangles.push_back(tri);
    }
    return m;
}

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

template <typename T>
double read_binary(std::istream& in) {
    T value;
    in.read(reinterpret_cast<char*>(&value), sizeof value);
    return static_cast<double>(value);
}

double read_value(std::istream& in, PlyType type, bool ascii) {
    if (ascii) {
        double v;
        in >> v;
        return v;
    }
    switch (type) {
        case PlyType::i8: return read_binary<std::int8_t>(in);
        case PlyType::u8: return read_binary<std::uint8_t>(in);
        case PlyType::i16: return read_binary<std::int16_t>(in);
        case PlyType::u16: return read_binary<std::uint16_t>(in);
        case PlyType::i32: return read_binary<std::int32_t>(in);
        case PlyType::u32: return read_binary<std::uint32_t>(in);
        case PlyType::f32: return read_binary<float>(in);
        case PlyType::f64: return read_binary<double>(in);
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
    bool ascii = false;
    std::vector<PlyElement> elements;
    while (std::getline(in, line)) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream ls(line);
        std::string tag;
        ls >> tag;
        if (tag == "format") {
            std::string format;
            ls >> format;
            if (format == "ascii") ascii = true;
            else if (format != "binary_little_endian")
                fail("{}: unsupported PLY format '{}' (ascii or binary_little_endian)", path.string(), format);
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
                    const auto count = static_cast<std::size_t>(read_value(in, prop.count_type, ascii));
                    std::vector<std::uint32_t> idx(count);
                    for (auto& x : idx) x = static_cast<std::uint32_t>(read_value(in, prop.type, ascii));
                    if (e.name == "face" && (prop.name == "vertex_indices" || prop.name == "vertex_index"))
                        for (std::size_t k = 1; k + 1 < count; ++k) m.triangles.push_back({idx[0], idx[k], idx[k + 1]});
                    continue;
                }
                const double value = read_value(in, prop.type, ascii);
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

void transform_mesh(TriangleMesh& mesh, const Transform& to_world, bool flip_normals) {
    for (Vec3& p : mesh.positions) p = to_world.point(p);
    if (!mesh.normals.empty()) {
        const Transform inverse = to_world.inverse();  // normals go by the inverse transpose
        for (Vec3& n : mesh.normals) {
            Vec3 out;
            for (int r = 0; r < 3; ++r) out[r] = inverse.m[0][r] * n.x + inverse.m[1][r] * n.y + inverse.m[2][r] * n.z;
            n = normalize(out) * (flip_normals ? -1.0 : 1.0);
        }
    }
    // A mirroring transform turns counter-clockwise into clockwise: keep the geometric normal outward.
    const Vec3 a = to_world.vector({1, 0, 0}), b = to_world.vector({0, 1, 0}), c = to_world.vector({0, 0, 1});
    const bool mirrored = dot(cross(a, b), c) < 0;
    if (mirrored != flip_normals)
        for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
}

}  // namespace surfscatter::render
