#pragma once
// What the analytic shapes (sphere, cylinder, disk) share: an object-to-world transform, the ray in object space,
// and the similarity check of shapes whose area sampling needs one.
#include <cmath>

#include "surfscatter/render/properties.hpp"
#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

// The uniform scale of a transform made of rotations, translations and one uniform scale, or nothing.
inline std::optional<double> similarity_scale(const Transform& t) {
    const Vec3 ex = t.vector({1, 0, 0}), ey = t.vector({0, 1, 0}), ez = t.vector({0, 0, 1});
    const double s = ex.length();
    const double tolerance = 1e-9 * s;
    if (!(s > 0) || std::abs(ey.length() - s) > tolerance || std::abs(ez.length() - s) > tolerance ||
        std::abs(dot(ex, ey)) > tolerance * s || std::abs(dot(ex, ez)) > tolerance * s || std::abs(dot(ey, ez)) > tolerance * s)
        return std::nullopt;
    return s;
}

// Solutions of a t^2 + b t + c = 0 (a != 0), smaller first, by the cancellation-free formula.
inline bool solve_quadratic(double a, double b, double c, double& t0, double& t1) {
    const double discriminant = b * b - 4 * a * c;
    if (discriminant < 0) return false;
    const double q = -0.5 * (b + std::copysign(std::sqrt(discriminant), b));
    t0 = q / a;
    t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
    return true;
}

}  // namespace surfscatter::render
