#pragma once
// What a mesh reader returns: finite positions, unit normals and finite uvs (one per vertex or none), triangle
// indices in range.
#include "fuzz_common.hpp"
#include "surfscatter/render/mesh.hpp"

namespace surfscatter::fuzz {

inline void check_mesh(const render::TriangleMesh& mesh) {
    FUZZ_CHECK(!mesh.triangles.empty());
    for (const Vec3& p : mesh.positions) FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    FUZZ_CHECK(mesh.normals.empty() || mesh.normals.size() == mesh.positions.size());
    FUZZ_CHECK(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size());
    for (const Vec3& n : mesh.normals) FUZZ_CHECK(std::abs(n.length() - 1.0) < 1e-9);
    for (const Vec2& uv : mesh.uvs) FUZZ_CHECK(std::isfinite(uv.x) && std::isfinite(uv.y));
    for (const auto& t : mesh.triangles)
        for (std::uint32_t i : t) FUZZ_CHECK(i < mesh.positions.size());
}

}  // namespace surfscatter::fuzz
