#pragma once
// Affine 4x4 transforms as used by Mitsuba's to_world: points, vectors and normals, composition and inverse.
#include <array>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::render {

struct Transform {
    std::array<std::array<double, 4>, 4> m{};  // row-major; last row (0, 0, 0, 1) for affine transforms

    Transform();  // identity
    static Transform from_rows(const std::array<double, 16>& values);
    static Transform translate(const Vec3& t);
    static Transform scale(const Vec3& s);
    static Transform rotate(const Vec3& axis, double angle_degrees);
    // Mitsuba's look_at: local +z toward target, +y up, +x = cross(up, dir) (to the viewer's left).
    static Transform look_at(const Vec3& origin, const Vec3& target, const Vec3& up);

    Transform operator*(const Transform& o) const;
    Transform inverse() const;  // throws Error if singular
    Vec3 point(const Vec3& p) const {  // inline: camera rays and texture coordinates are transformed per sample
        Vec3 out;
        for (int r = 0; r < 3; ++r) out[r] = m[r][0] * p.x + m[r][1] * p.y + m[r][2] * p.z + m[r][3];
        const double w = m[3][0] * p.x + m[3][1] * p.y + m[3][2] * p.z + m[3][3];
        return w == 1.0 ? out : out / w;
    }
    Vec3 vector(const Vec3& v) const {
        Vec3 out;
        for (int r = 0; r < 3; ++r) out[r] = m[r][0] * v.x + m[r][1] * v.y + m[r][2] * v.z;
        return out;
    }
    Vec3 normal(const Vec3& n) const;  // transformed by the inverse transpose, normalised
};

}  // namespace surfscatter::render
