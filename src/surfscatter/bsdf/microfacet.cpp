#include "surfscatter/bsdf/microfacet.hpp"

#include "surfscatter/core/error.hpp"

#include <cmath>

namespace surfscatter::bsdf {

void require_microfacet_alpha(double alpha, const char* what) {
    if (!(alpha >= kMinMicrofacetAlpha && alpha <= kMaxMicrofacetAlpha))
        fail("{} must be between {} and {}, got {}", what, kMinMicrofacetAlpha, kMaxMicrofacetAlpha, alpha);
}

LayFrame::LayFrame(double angle_rad)
    : angle_(angle_rad), cos_(std::cos(angle_rad)), sin_(std::sin(angle_rad)), turned_(angle_rad != 0) {
    if (!std::isfinite(angle_rad)) fail("lay_angle must be finite, got {}", angle_rad);
}

double GgxDistribution::D(const Vec3& h) const {
    if (h.z <= 0) return 0.0;
    const double c2 = h.z * h.z;
    if (!isotropic()) {
        const double x = h.x / alpha_x_, y = h.y / alpha_y_;
        const double denom = c2 + x * x + y * y;  // = cos^2 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))
        return 1.0 / (kPi * alpha_x_ * alpha_y_ * denom * denom);
    }
    const double a2 = alpha_x_ * alpha_x_;
    const double s2 = std::max(0.0, 1.0 - c2);
    const double denom = a2 * c2 + s2;  // = cos^2 (a^2 + tan^2), no division by cos
    return a2 / (kPi * denom * denom);
}

double GgxDistribution::lambda(const Vec3& w) const {
    if (w.z <= 0) return 0.0;
    const double c2 = w.z * w.z;
    // (sqrt(1 + a(phi)^2 tan^2) - 1) / 2, written without tan so that grazing w stays finite.
    if (!isotropic()) {
        const double x = alpha_x_ * w.x, y = alpha_y_ * w.y;
        return 0.5 * (std::sqrt(c2 + x * x + y * y) / w.z - 1.0);
    }
    const double s2 = std::max(0.0, 1.0 - c2);
    return 0.5 * (std::sqrt(c2 + alpha_x_ * alpha_x_ * s2) / w.z - 1.0);
}

double GgxDistribution::visible_density(const Vec3& w, const Vec3& h) const {
    const double wh = dot(w, h);
    if (wh <= 0 || w.z <= 0) return 0.0;
    return G1(w) * wh * D(h) / w.z;
}

Vec3 GgxDistribution::sample_visible(const Vec3& w, Vec2 u) const {
    // Stretch to the unit-roughness configuration, sample the projected hemisphere, unstretch (Heitz 2018).
    const Vec3 wh = normalize(Vec3(alpha_x_ * w.x, alpha_y_ * w.y, w.z));
    const double len2 = wh.x * wh.x + wh.y * wh.y;
    const Vec3 t1 = len2 > 0 ? Vec3(-wh.y, wh.x, 0) / std::sqrt(len2) : Vec3(1, 0, 0);
    const Vec3 t2 = cross(wh, t1);
    const double r = std::sqrt(u.x);
    const double phi = kTwoPi * u.y;
    const double p1 = r * std::cos(phi);
    double p2 = r * std::sin(phi);
    const double s = 0.5 * (1.0 + wh.z);
    p2 = (1.0 - s) * std::sqrt(std::max(0.0, 1.0 - p1 * p1)) + s * p2;
    const double p3 = std::sqrt(std::max(0.0, 1.0 - p1 * p1 - p2 * p2));
    const Vec3 nh = t1 * p1 + t2 * p2 + wh * p3;
    return normalize(Vec3(alpha_x_ * nh.x, alpha_y_ * nh.y, std::max(1e-12, nh.z)));
}

double BeckmannDistribution::D(const Vec3& h) const {
    if (h.z <= 0) return 0.0;
    const double c2 = h.z * h.z;
    if (!isotropic()) {
        const double x = h.x / alpha_x_, y = h.y / alpha_y_;
        return std::exp(-(x * x + y * y) / c2) / (kPi * alpha_x_ * alpha_y_ * c2 * c2);
    }
    const double t2 = std::max(0.0, 1.0 - c2) / c2;
    const double a2 = alpha_x_ * alpha_x_;
    return std::exp(-t2 / a2) / (kPi * a2 * c2 * c2);
}

double BeckmannDistribution::lambda(const Vec3& w) const {
    if (w.z <= 0) return 0.0;
    double a = 0;  // cot(theta) / alpha(phi)
    if (!isotropic()) {
        const double projected = std::hypot(alpha_x_ * w.x, alpha_y_ * w.y);  // alpha(phi) sin(theta)
        if (projected == 0) return 0.0;
        a = w.z / projected;
    } else {
        const double s = sin_theta(w);
        if (s == 0) return 0.0;
        a = w.z / (alpha_x_ * s);
    }
    // Walter et al. 2007 exact form.
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

Vec3 BeckmannDistribution::sample_projected(Vec2 u) const {
    const double r2 = -std::log1p(-std::min(u.x, 1.0 - 1e-16));
    if (!isotropic()) {
        // D(h) cos(theta_h) is the slope density exp(-(sx^2/ax^2 + sy^2/ay^2)) / (pi ax ay): the unit Gaussian
        // (|s|^2 = r2 exponential, uniform azimuth) stretched by (ax, ay); h is the normal of that slope.
        const double r = std::sqrt(r2), phi = kTwoPi * u.y;
        return normalize(Vec3(alpha_x_ * r * std::cos(phi), alpha_y_ * r * std::sin(phi), 1.0));
    }
    // D(h) cos(theta_h): tan^2 theta_h = -alpha^2 ln(1 - u1), uniform azimuth.
    const double t2 = alpha_x_ * alpha_x_ * r2;
    const double c = 1.0 / std::sqrt(1.0 + t2);
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = kTwoPi * u.y;
    return {s * std::cos(phi), s * std::sin(phi), c};
}

}  // namespace surfscatter::bsdf
