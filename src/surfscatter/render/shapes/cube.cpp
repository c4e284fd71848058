// Mitsuba's `cube` shape: [-1, 1]^3 with outward normals (flat faces), each face's uv covering [0, 1]^2.
//
// Supported: `to_world`, `flip_normals`.
// Differences: the orientation of the uv square on each face may differ from Mitsuba's (a texture on a cube can
// appear rotated).
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

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

ShapeGeometry plugins::cube(Properties& props) {
    TriangleMesh mesh = make_cube();
    transform_mesh(mesh, props.get_transform("to_world"), props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
