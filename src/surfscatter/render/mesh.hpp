#pragma once
// Triangle meshes of the scene: Mitsuba's built-in shapes (rectangle, disk, cube) and OBJ / PLY files.
#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

struct TriangleMesh {
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;  // per vertex, optional (empty: flat shading)
    std::vector<Vec2> uvs;      // per vertex, optional
    std::vector<std::array<std::uint32_t, 3>> triangles;
};

TriangleMesh make_rectangle();             // [-1, 1]^2 at z = 0, normal +z, uv = (x + 1, y + 1) / 2
TriangleMesh make_disk(int segments = 256); // unit disk at z = 0, normal +z, uv = (r, phi / 2pi) as in Mitsuba
TriangleMesh make_cube();                  // [-1, 1]^3, outward normals, flat faces
// Wavefront OBJ (v, vt, vn, f with polygons fanned into triangles; other statements skipped as OBJ allows).
TriangleMesh load_obj(const std::filesystem::path& path);
// PLY, ascii or binary_little_endian: vertex x y z [nx ny nz] [u v | s t | texture_u texture_v], face lists.
TriangleMesh load_ply(const std::filesystem::path& path);

void transform_mesh(TriangleMesh& mesh, const Transform& to_world, bool flip_normals);

}  // namespace surfscatter::render
