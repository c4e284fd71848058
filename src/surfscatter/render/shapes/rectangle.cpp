// Mitsuba's `rectangle` shape: the square [-1, 1]^2 in the plane z = 0, normal +z, uv = (x + 1, y + 1) / 2.
//
// Supported: `to_world`, `flip_normals`. Two triangles (exact: the shape is planar).
// Differences: none.
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

TriangleMesh make_rectangle() {
    TriangleMesh m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.normals.assign(4, {0, 0, 1});
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    return m;
}

ShapeGeometry plugins::rectangle(Properties& props) {
    TriangleMesh mesh = make_rectangle();
    transform_mesh(mesh, props.get_transform("to_world"), props.get_bool("flip_normals", false));
    return mesh;
}

}  // namespace surfscatter::render
