// Mitsuba's `obj` shape: a Wavefront OBJ triangle mesh.
//
// Supported: `filename`, `face_normals` (default false), `flip_tex_coords` (default true: v becomes 1 - v, as in
// Mitsuba), `flip_normals`, `to_world`. Statements v, vt, vn and f (v, v/vt, v//vn, v/vt/vn, negative indices;
// polygons are fanned into triangles); corners with the same index triple share a vertex, and a mesh without
// normals gets Mitsuba's angle-weighted smooth vertex normals unless face_normals is set. Other statements
// (materials, groups, smoothing groups) are skipped, as OBJ allows and Mitsuba does.
// Differences: none.
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

// 0-based index of an OBJ reference (1-based, or negative = relative to the end); -1 for "not given".
long obj_index(long index, std::size_t count, const std::filesystem::path& path, int line) {
    const long resolved = index < 0 ? static_cast<long>(count) + index : index - 1;
    if (index == 0 || resolved < 0 || resolved >= static_cast<long>(count))
        fail("{}:{}: OBJ index {} out of range (1..{})", path.string(), line, index, count);
    return resolved;
}

}  // namespace

TriangleMesh load_obj(const std::filesystem::path& path, bool flip_tex_coords) {
    std::ifstream in(path);
    if (!in) fail("cannot open OBJ file {}", path.string());
    std::vector<Vec3> v, vn;
    std::vector<Vec2> vt;
    using Key = std::tuple<long, long, long>;  // v, vt, vn (-1: absent)
    std::map<Key, std::uint32_t> vertex_of;
    std::vector<Key> keys;
    std::vector<std::array<std::uint32_t, 3>> triangles;
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
            if (flip_tex_coords) t.y = 1 - t.y;
            vt.push_back(t);
        } else if (tag == "f") {
            std::vector<std::uint32_t> corners;
            std::string item;
            while (ls >> item) {
                long a = 0, b = 0, n = 0;
                Key key{-1, -1, -1};
                if (std::sscanf(item.c_str(), "%ld/%ld/%ld", &a, &b, &n) == 3)
                    key = {obj_index(a, v.size(), path, line), obj_index(b, vt.size(), path, line),
                           obj_index(n, vn.size(), path, line)};
                else if (std::sscanf(item.c_str(), "%ld//%ld", &a, &n) == 2)
                    key = {obj_index(a, v.size(), path, line), -1, obj_index(n, vn.size(), path, line)};
                else if (std::sscanf(item.c_str(), "%ld/%ld", &a, &b) == 2)
                    key = {obj_index(a, v.size(), path, line), obj_index(b, vt.size(), path, line), -1};
                else if (std::sscanf(item.c_str(), "%ld", &a) == 1)
                    key = {obj_index(a, v.size(), path, line), -1, -1};
                else
                    fail("{}:{}: malformed face vertex '{}'", path.string(), line, item);
                const auto [it, inserted] = vertex_of.emplace(key, static_cast<std::uint32_t>(keys.size()));
                if (inserted) keys.push_back(key);
                corners.push_back(it->second);
            }
            if (corners.size() < 3) fail("{}:{}: a face needs at least 3 vertices", path.string(), line);
            for (std::size_t i = 1; i + 1 < corners.size(); ++i) triangles.push_back({corners[0], corners[i], corners[i + 1]});
        }
    }
    if (triangles.empty()) fail("OBJ file {} has no faces", path.string());
    TriangleMesh m;
    m.triangles = std::move(triangles);
    const bool with_uv = std::all_of(keys.begin(), keys.end(), [](const Key& k) { return std::get<1>(k) >= 0; });
    const bool with_n = std::all_of(keys.begin(), keys.end(), [](const Key& k) { return std::get<2>(k) >= 0; });
    for (const Key& k : keys) {
        m.positions.push_back(v[static_cast<std::size_t>(std::get<0>(k))]);
        if (with_uv) m.uvs.push_back(vt[static_cast<std::size_t>(std::get<1>(k))]);
        if (with_n) m.normals.push_back(normalize(vn[static_cast<std::size_t>(std::get<2>(k))]));
    }
    return m;
}

ShapeGeometry plugins::obj(Properties& props) {
    TriangleMesh mesh = load_obj(props.get_file("filename"), props.get_bool("flip_tex_coords", true));
    finish_mesh(mesh, props.get_bool("face_normals", false), props.get_transform("to_world"),
                props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
