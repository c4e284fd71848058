#include "surfscatter/bsdf/microfacet.hpp"

#include "surfscatter/core/error.hpp"

#include <cmath>

namespace surfscatter::bsdf {

void require_microfacet_alpha(double alpha, const char* what) {
    if (!(alpha >= kMinMicrofacetAlpha && alpha <= kMaxMicrofacetAlpha))
        fail("{} must be between {} and {}, got {}", what, kMinMicrofacetAlpha, kMaxMicrofacetAlpha, alpha);
}

double GgxDistribution::D(const Vec3& h) const {
    if (h.z <= 0) return 0.0;
    const double a2 = alpha_ * alpha_;
    const double c2 = h.z * h.z;
    const double s2 = std::max(0.0, 1.0 - c2);
    const double denom = a2 * c2 + s2;  // = cos^2 (a^2 + tan^2), no division by cos
    return a2 / (kPi * denom * denom);
}

double GgxDistribution::lambda(const Vec3& w) const {
    if (w.z <= 0) return 0.0;
    const double c2 = w.z * w.z;
    const double s2 = std::max(0.0, 1.0 - c2);
    // (sqrt(1 + a^2 tan^2) - 1) / 2, written without tan so that grazing w stays finite.
    return 0.5 * (std::sqrt(c2 + alpha_ * alpha_ * s2) / w.z - 1.0);
}

double GgxDistribution::visible_density(const Vec3& w, const Vec3& h) const {
    const double wh = dot(w, h);
    if (wh <= 0 || w.z <= 0) return 0.0;
    return G1(w) * wh * D(h) / w.z;
}

Vec3 GgxDistribution::sample_visible(const Vec3& w, Vec2 u) const {
    // Stretch to the unit-roughness configuration, sample the projected hemisphere, unstretch (Heitz 2018).
    const Vec3 wh = normalize(Vec3(alpha_ * w.x, alpha_ * w.y, w.z));
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
    return normalize(Vec3(alpha_ * nh.x, alpha_ * nh.y, std::max(1e-12, nh.z)));
}

double BeckmannDistribution::D(const Vec3& h) const {
    if (h.z <= 0) return 0.0;
    const double c2 = h.z * h.z;
    const double t2 = std::max(0.0, 1.0 - c2) / c2;
    const double a2 = alpha_ * alpha_;
    return std::exp(-t2 / a2) / (kPi * a2 * c2 * c2);
}

double BeckmannDistribution::lambda(const Vec3& w) const {
    if (w.z <= 0) return 0.0;
    const double s = sin_theta(w);
    if (s == 0) return 0.0;
    const double a = w.z / (alpha_ * s);  // cot(theta) / alpha
    // Walter et al. 2007 exact form.
    return 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(kPi));
}

Vec3 BeckmannDistribution::sample_projected(Vec2 u) const {
    // D(h) cos(theta_h): tan^2 theta_h = -alpha^2 ln(1 - u1), uniform azimuth.
    const double t2 = -alpha_ * alpha_ * std::log1p(-std::min(u.x, 1.0 - 1e-16));
    const double c = 1.0 / std::sqrt(1.0 + t2);
    const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double phi = kTwoPi * u.y;
    return {s * std::cos(phi), s * std::sin(phi), c};
}

}  // namespace surfscatter::bsdf
