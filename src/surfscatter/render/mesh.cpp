#include "surfscatter/render/mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

void recompute_vertex_normals(TriangleMesh& mesh) {
    mesh.normals.assign(mesh.positions.size(), Vec3());
    for (const auto& t : mesh.triangles) {
        const Vec3 face = cross(mesh.positions[t[1]] - mesh.positions[t[0]], mesh.positions[t[2]] - mesh.positions[t[0]]);
        const double length = face.length();
        if (!(length > 0)) continue;
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = mesh.positions[t[static_cast<std::size_t>(k)]];
            const Vec3 e1 = mesh.positions[t[static_cast<std::size_t>((k + 1) % 3)]] - p;
            const Vec3 e2 = mesh.positions[t[static_cast<std::size_t>((k + 2) % 3)]] - p;
            const double l1 = e1.length(), l2 = e2.length();
            if (!(l1 > 0 && l2 > 0)) continue;
            const double angle = std::acos(std::clamp(dot(e1, e2) / (l1 * l2), -1.0, 1.0));
            mesh.normals[t[static_cast<std::size_t>(k)]] += face * (angle / length);
        }
    }
    for (Vec3& n : mesh.normals) {
        const double length = n.length();
        n = length > 0 ? n / length : Vec3();  // an unused or degenerate vertex
    }
}

void finish_mesh(TriangleMesh& mesh, bool face_normals, const Transform& to_world, bool flip_normals) {
    if (face_normals) mesh.normals.clear();
    else if (mesh.normals.empty()) recompute_vertex_normals(mesh);
    transform_mesh(mesh, to_world, flip_normals);
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
