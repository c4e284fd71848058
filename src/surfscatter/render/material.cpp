#include "surfscatter/render/material.hpp"

#include <cmath>

namespace surfscatter::render {

Vec2 square_to_uniform_disk_concentric(Vec2 u) {
    // Shirley & Chiu 1997.
    const double a = 2 * u.x - 1, b = 2 * u.y - 1;
    if (a == 0 && b == 0) return {0, 0};
    double r = 0, phi = 0;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (kPi / 4) * (b / a);
    } else {
        r = b;
        phi = kPi / 2 - (kPi / 4) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

Vec3 square_to_cosine_hemisphere(Vec2 u) {
    const Vec2 d = square_to_uniform_disk_concentric(u);
    return {d.x, d.y, std::sqrt(std::max(0.0, 1 - d.x * d.x - d.y * d.y))};
}

}  // namespace surfscatter::render
