#pragma once
// Triangle meshes of the scene: Mitsuba's built-in rectangle and cube, and OBJ / PLY / serialized files
// (shapes/*.cpp document each plugin).
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
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
TriangleMesh make_cube();                  // [-1, 1]^3, outward normals, flat faces, each face uv [0, 1]^2
// Largest mesh file read (docs/RELIABILITY.md); the memory available is checked as well.
inline constexpr std::uint64_t kMaxMeshFileBytes = std::uint64_t{4} << 30;

// Wavefront OBJ (v, vt, vn, f with polygons fanned into triangles; other statements skipped as OBJ allows).
// Corners with the same (v, vt, vn) indices share a vertex. flip_tex_coords maps v to 1 - v (Mitsuba's default).
// Errors name file:line. parse_obj reads the file's text (`name` names it in messages).
TriangleMesh load_obj(const std::filesystem::path& path, bool flip_tex_coords = true);
TriangleMesh parse_obj(std::string_view text, const std::string& name, bool flip_tex_coords = true);
// PLY, ascii or binary (little or big endian): vertex x y z [nx ny nz] [u v | s t | texture_u texture_v], face lists.
// Errors name the file (and the header line). parse_ply reads the file's bytes.
TriangleMesh load_ply(const std::filesystem::path& path);
TriangleMesh parse_ply(std::string_view bytes, const std::string& name);
// Mitsuba's .serialized format (zlib-compressed, versions 3 and 4): mesh number `shape_index` of the file.
// `face_normals` is set if the file asks for face normals.
TriangleMesh load_serialized(const std::filesystem::path& path, int shape_index, bool& face_normals);
TriangleMesh parse_serialized(std::string_view bytes, const std::string& name, int shape_index, bool& face_normals);

// Mitsuba's vertex normals for a mesh that has none: at each vertex, the face normals of the triangles around it
// weighted by the triangle's angle at that vertex.
void recompute_vertex_normals(TriangleMesh& mesh);

// What every mesh plugin does after loading: face_normals drops the vertex normals, a mesh without them gets
// Mitsuba's smooth normals, then to_world and flip_normals apply.
void finish_mesh(TriangleMesh& mesh, bool face_normals, const Transform& to_world, bool flip_normals);

void transform_mesh(TriangleMesh& mesh, const Transform& to_world, bool flip_normals);

}  // namespace surfscatter::render
