#include "surfscatter/render/transform.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::render {

Transform::Transform() {
    for (int i = 0; i < 4; ++i) m[i][i] = 1.0;
}

Transform Transform::from_rows(const std::array<double, 16>& values) {
    Transform t;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) t.m[r][c] = values[static_cast<std::size_t>(4 * r + c)];
    return t;
}

Transform Transform::translate(const Vec3& v) {
    Transform t;
    t.m[0][3] = v.x;
    t.m[1][3] = v.y;
    t.m[2][3] = v.z;
    return t;
}

Transform Transform::scale(const Vec3& s) {
    Transform t;
    t.m[0][0] = s.x;
    t.m[1][1] = s.y;
    t.m[2][2] = s.z;
    return t;
}

Transform Transform::rotate(const Vec3& axis_in, double angle_degrees) {
    const double length = axis_in.length();
    if (!(length > 0)) fail("rotation axis must be non-zero");
    const Vec3 a = axis_in / length;
    const double s = std::sin(angle_degrees * kDegree), c = std::cos(angle_degrees * kDegree);
    Transform t;
    t.m[0] = {a.x * a.x + (1 - a.x * a.x) * c, a.x * a.y * (1 - c) - a.z * s, a.x * a.z * (1 - c) + a.y * s, 0};
    t.m[1] = {a.x * a.y * (1 - c) + a.z * s, a.y * a.y + (1 - a.y * a.y) * c, a.y * a.z * (1 - c) - a.x * s, 0};
    t.m[2] = {a.x * a.z * (1 - c) - a.y * s, a.y * a.z * (1 - c) + a.x * s, a.z * a.z + (1 - a.z * a.z) * c, 0};
    return t;
}

Transform Transform::look_at(const Vec3& origin, const Vec3& target, const Vec3& up) {
    const Vec3 d = target - origin;
    if (!(d.length() > 0)) fail("lookat: origin and target coincide");
    const Vec3 dir = normalize(d);
    const Vec3 l = cross(up, dir);
    if (!(l.length() > 1e-12)) fail("lookat: up vector is parallel to the viewing direction");
    const Vec3 left = normalize(l);
    const Vec3 new_up = cross(dir, left);
    Transform t;
    for (int r = 0; r < 3; ++r) {
        t.m[r][0] = left[r];
        t.m[r][1] = new_up[r];
        t.m[r][2] = dir[r];
        t.m[r][3] = origin[r];
    }
    return t;
}

Transform Transform::operator*(const Transform& o) const {
    Transform t;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
            double sum = 0;
            for (int k = 0; k < 4; ++k) sum += m[r][k] * o.m[k][c];
            t.m[r][c] = sum;
        }
    return t;
}

Transform Transform::inverse() const {
    // Gauss-Jordan with partial pivoting on [M | I].
    std::array<std::array<double, 8>, 4> a{};
    for (int r = 0; r < 4; ++r) {
        for (int c = 0; c < 4; ++c) a[r][c] = m[r][c];
        a[r][4 + r] = 1.0;
    }
    for (int col = 0; col < 4; ++col) {
        int pivot = col;
        for (int r = col + 1; r < 4; ++r)
            if (std::abs(a[r][col]) > std::abs(a[pivot][col])) pivot = r;
        if (std::abs(a[pivot][col]) < 1e-300) fail("transform is singular and cannot be inverted");
        std::swap(a[col], a[pivot]);
        const double inv = 1.0 / a[col][col];
        for (double& x : a[col]) x *= inv;
        for (int r = 0; r < 4; ++r) {
            if (r == col) continue;
            const double f = a[r][col];
            for (int c = 0; c < 8; ++c) a[r][c] -= f * a[col][c];
        }
    }
    Transform t;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) t.m[r][c] = a[r][4 + c];
    return t;
}

Vec3 Transform::normal(const Vec3& n) const {
    const Transform inv = inverse();
    Vec3 out;
    for (int r = 0; r < 3; ++r) out[r] = inv.m[0][r] * n.x + inv.m[1][r] * n.y + inv.m[2][r] * n.z;
    return normalize(out);
}

}  // namespace surfscatter::render
