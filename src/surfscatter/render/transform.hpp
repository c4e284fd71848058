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
    Vec3 point(const Vec3& p) const;
    Vec3 vector(const Vec3& v) const;
    Vec3 normal(const Vec3& n) const;  // transformed by the inverse transpose, normalised
};

}  // namespace surfscatter::render
