#pragma once
// Microfacet normal distributions (pbrt-v4 TrowbridgeReitzDistribution / Heitz 2014, 2018 conventions), isotropic
// (alpha) or anisotropic (alpha_x along the frame's x axis, alpha_y along y): D(h) normalised so that
// integral D(h) cos(theta_h) dw_h = 1, Smith Lambda for the height-correlated masking-shadowing
// G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Local frame, z = macro normal; a lay at angle A is the caller's rotation of
// the directions into the (x, y) = (u, v) frame.
//   GGX:      D = 1 / (pi ax ay (h_z^2 + h_x^2/ax^2 + h_y^2/ay^2)^2),
//             Lambda = (sqrt(w_z^2 + ax^2 w_x^2 + ay^2 w_y^2) / w_z - 1) / 2;
//   Beckmann: D = exp(-(h_x^2/ax^2 + h_y^2/ay^2) / h_z^2) / (pi ax ay h_z^4), Lambda of a = w_z / sqrt(ax^2 w_x^2 +
//             ay^2 w_y^2) (Walter et al. 2007).
// Both are slope distributions stretched by (ax, ay) from the unit one, so ax = ay = alpha is the isotropic form;
// that case keeps the isotropic code (bitwise the same results, and the GGX eval benchmark's speed). Accuracy:
// closed forms, round-off only; tests/bsdf/test_ggx.cpp checks the normalisation of D and of the visible densities by
// midpoint quadrature to 2e-3 and every sampler by chi-square.
#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

// Roughness alpha accepted for GGX and Beckmann (docs/RELIABILITY.md): below 1e-4 the lobe is narrower than the
// albedo quadrature resolves (an albedo of 33 at 1e-8), above 100 the surface is all grazing facets; outside that
// alpha^2 and its inverse leave the range where D and Lambda are evaluated without overflow.
inline constexpr double kMinMicrofacetAlpha = 1e-4;
inline constexpr double kMaxMicrofacetAlpha = 100;
// Throws Error "<what> must be between 0.0001 and 100, got <alpha>" outside that range (also NaN).
void require_microfacet_alpha(double alpha, const char* what);

class GgxDistribution {
public:
    explicit GgxDistribution(double alpha) : alpha_x_(alpha), alpha_y_(alpha) {}
    GgxDistribution(double alpha_x, double alpha_y) : alpha_x_(alpha_x), alpha_y_(alpha_y) {}
    double alpha_x() const { return alpha_x_; }
    double alpha_y() const { return alpha_y_; }
    bool isotropic() const { return alpha_x_ == alpha_y_; }
    double D(const Vec3& h) const;
    double lambda(const Vec3& w) const;
    double G1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
    double G2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
    // Visible normals seen from w (Heitz 2018): density D_w(h) = G1(w) max(0, w.h) D(h) / cos(theta_w).
    double visible_density(const Vec3& w, const Vec3& h) const;
    Vec3 sample_visible(const Vec3& w, Vec2 u) const;

private:
    double alpha_x_, alpha_y_;
};

// Beckmann with alpha = rms slope (THEORY 4.2); sampled by D(h) cos(theta_h) (no closed-form visible sampler).
class BeckmannDistribution {
public:
    explicit BeckmannDistribution(double alpha) : alpha_x_(alpha), alpha_y_(alpha) {}
    BeckmannDistribution(double alpha_x, double alpha_y) : alpha_x_(alpha_x), alpha_y_(alpha_y) {}
    double alpha_x() const { return alpha_x_; }
    double alpha_y() const { return alpha_y_; }
    bool isotropic() const { return alpha_x_ == alpha_y_; }
    double D(const Vec3& h) const;
    double lambda(const Vec3& w) const;
    double G2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
    // Density D(h) cos(theta_h) over the hemisphere of normals, and its sampler.
    double projected_density(const Vec3& h) const { return D(h) * h.z; }
    Vec3 sample_projected(Vec2 u) const;

private:
    double alpha_x_, alpha_y_;
};

// The lay frame (u, v, z) of an anisotropic lobe whose u axis lies at angle A from x towards y (surface::
// EllipticalStatistics' convention): local-frame directions turned by -A about z, and back; A = 0 is the identity
// without arithmetic (isotropic and unturned results stay bitwise what they were).
class LayFrame {
public:
    explicit LayFrame(double angle_rad = 0);
    double angle() const { return angle_; }
    bool turned() const { return turned_; }
    Vec3 to_lay(const Vec3& w) const {
        if (!turned_) return w;
        return {cos_ * w.x + sin_ * w.y, -sin_ * w.x + cos_ * w.y, w.z};
    }
    Vec3 from_lay(const Vec3& w) const {
        if (!turned_) return w;
        return {cos_ * w.x - sin_ * w.y, sin_ * w.x + cos_ * w.y, w.z};
    }

private:
    double angle_, cos_, sin_;
    bool turned_;
};

// Solid-angle density of wo = reflect(wi, h) given the density of h: p(wo) = p(h) / (4 |wo.h|).
inline double reflection_jacobian(const Vec3& wo, const Vec3& h) { return 1.0 / (4.0 * std::abs(dot(wo, h))); }
inline Vec3 reflect(const Vec3& w, const Vec3& h) { return 2.0 * dot(w, h) * h - w; }

}  // namespace surfscatter::bsdf
