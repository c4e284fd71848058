// Mitsuba's `obj` shape: a Wavefront OBJ triangle mesh.
//
// Supported: `filename`, `face_normals` (default false), `flip_tex_coords` (default true: v becomes 1 - v, as in
// Mitsuba), `flip_normals`, `to_world`. Statements v, vt, vn and f (v, v/vt, v//vn, v/vt/vn, negative indices;
// polygons are fanned into triangles); corners with the same index triple share a vertex, and a mesh without
// normals gets Mitsuba's angle-weighted smooth vertex normals unless face_normals is set. Other statements
// (materials, groups, smoothing groups) are skipped, as OBJ allows and Mitsuba does. Every malformed line is an
// error naming file:line: numbers must be whole tokens, indices in range, normals non-zero, a vertex weight 1.
// Differences: none.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <string_view>
#include <tuple>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

struct ObjParser {
    const std::string& name;
    int line = 0;

    template <typename... Args>
    [[noreturn]] void error(fmt::format_string<Args...> format, Args&&... args) const {
        throw Error(fmt::format("{}:{}: ", name, line) + fmt::format(format, std::forward<Args>(args)...));
    }

    double number(const std::string& token) const {
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(token.c_str(), &end);
        if (end != token.c_str() + token.size() || !std::isfinite(v) || (errno == ERANGE && std::abs(v) > 1.0))
            error("'{}' is not a finite number", printable(token));
        return v;
    }

    // 0-based index of an OBJ reference (1-based, or negative = relative to the end) into `count` items.
    long index(std::string_view text, std::size_t count, const char* what) const {
        const std::string token(text);
        char* end = nullptr;
        errno = 0;
        const long long i = std::strtoll(token.c_str(), &end, 10);
        if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE)
            error("'{}' is not an OBJ {} index", printable(token), what);
        const long long n = static_cast<long long>(count);
        const long long resolved = i < 0 ? n + i : i - 1;
        if (i == 0 || resolved < 0 || resolved >= n) error("OBJ {} index {} out of range (1..{})", what, i, count);
        return static_cast<long>(resolved);
    }
};

std::vector<std::string> split_words(std::string_view line) {
    std::vector<std::string> words;
    for (std::size_t i = 0; i < line.size();) {
        while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
        std::size_t j = i;
        while (j < line.size() && line[j] != ' ' && line[j] != '\t' && line[j] != '\r') ++j;
        if (j > i) words.emplace_back(line.substr(i, j - i));
        i = j;
    }
    return words;
}

}  // namespace

TriangleMesh parse_obj(std::string_view text, const std::string& name, bool flip_tex_coords) {
    ObjParser parser{name};
    std::vector<Vec3> v, vn;
    std::vector<Vec2> vt;
    using Key = std::tuple<long, long, long>;  // v, vt, vn (-1: absent)
    std::map<Key, std::uint32_t> vertex_of;
    std::vector<Key> keys;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t start = 0; start < text.size();) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::vector<std::string> words = split_words(text.substr(start, end - start));
        start = end + 1;
        ++parser.line;
        if (words.empty() || words[0][0] == '#') continue;
        const std::string& tag = words[0];
        const std::size_t args = words.size() - 1;
        if (tag == "v") {
            // x y z, optionally the weight w of rational curves, which a polygon mesh must leave at 1.
            if (args != 3 && args != 4) parser.error("'v' needs x y z, got {} numbers", args);
            if (args == 4 && parser.number(words[4]) != 1.0) parser.error("vertex weight w must be 1 for a mesh");
            v.emplace_back(parser.number(words[1]), parser.number(words[2]), parser.number(words[3]));
        } else if (tag == "vn") {
            if (args != 3) parser.error("'vn' needs x y z, got {} numbers", args);
            const Vec3 n(parser.number(words[1]), parser.number(words[2]), parser.number(words[3]));
            if (!(n.length() > 0) || !std::isfinite(n.length()))
                parser.error("normal ({}, {}, {}) has no direction", n.x, n.y, n.z);
            vn.push_back(normalize(n));
        } else if (tag == "vt") {
            // u v, optionally a depth w that 2D textures do not use.
            if (args != 2 && args != 3) parser.error("'vt' needs u v, got {} numbers", args);
            if (args == 3) parser.number(words[3]);
            Vec2 t(parser.number(words[1]), parser.number(words[2]));
            if (flip_tex_coords) t.y = 1 - t.y;
            vt.push_back(t);
        } else if (tag == "f") {
            if (args < 3) parser.error("a face needs at least 3 vertices, got {}", args);
            std::vector<std::uint32_t> corners;
            for (std::size_t k = 1; k < words.size(); ++k) {
                const std::string_view item = words[k];
                const std::size_t slash1 = item.find('/');
                const std::size_t slash2 = slash1 == std::string_view::npos ? slash1 : item.find('/', slash1 + 1);
                if (slash2 != std::string_view::npos && item.find('/', slash2 + 1) != std::string_view::npos)
                    parser.error("malformed face vertex '{}'", printable(item));
                Key key{parser.index(item.substr(0, slash1), v.size(), "vertex"), -1, -1};
                if (slash1 != std::string_view::npos) {
                    const std::string_view uv = item.substr(
                        slash1 + 1, slash2 == std::string_view::npos ? std::string_view::npos : slash2 - slash1 - 1);
                    if (!uv.empty() || slash2 == std::string_view::npos)
                        std::get<1>(key) = parser.index(uv, vt.size(), "texture coordinate");
                    if (slash2 != std::string_view::npos)
                        std::get<2>(key) = parser.index(item.substr(slash2 + 1), vn.size(), "normal");
                }
                const auto [it, inserted] = vertex_of.emplace(key, static_cast<std::uint32_t>(keys.size()));
                if (inserted) keys.push_back(key);
                corners.push_back(it->second);
            }
            for (std::size_t i = 1; i + 1 < corners.size(); ++i) triangles.push_back({corners[0], corners[i], corners[i + 1]});
            if (keys.size() >= std::numeric_limits<std::uint32_t>::max() ||
                triangles.size() >= std::numeric_limits<std::uint32_t>::max())
                parser.error("more than 2^32 vertices or triangles");
        }
    }
    if (triangles.empty()) fail("OBJ file {} has no faces", name);
    TriangleMesh m;
    m.triangles = std::move(triangles);
    const bool with_uv = std::all_of(keys.begin(), keys.end(), [](const Key& k) { return std::get<1>(k) >= 0; });
    const bool with_n = std::all_of(keys.begin(), keys.end(), [](const Key& k) { return std::get<2>(k) >= 0; });
    for (const Key& k : keys) {
        m.positions.push_back(v[static_cast<std::size_t>(std::get<0>(k))]);
        if (with_uv) m.uvs.push_back(vt[static_cast<std::size_t>(std::get<1>(k))]);
        if (with_n) m.normals.push_back(vn[static_cast<std::size_t>(std::get<2>(k))]);
    }
    return m;
}

TriangleMesh load_obj(const std::filesystem::path& path, bool flip_tex_coords) {
    return parse_obj(read_input_file(path, "OBJ file", kMaxMeshFileBytes), path.string(), flip_tex_coords);
}

ShapeGeometry plugins::obj(Properties& props) {
    TriangleMesh mesh = load_obj(props.get_file("filename"), props.get_bool("flip_tex_coords", true));
    finish_mesh(mesh, props.get_bool("face_normals", false), props.get_transform("to_world"),
                props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
