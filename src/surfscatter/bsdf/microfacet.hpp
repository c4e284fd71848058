#pragma once
// Isotropic microfacet normal distributions (pbrt-v4 TrowbridgeReitzDistribution / Heitz 2014, 2018 conventions):
// D(h) normalised so that integral D(h) cos(theta_h) dw_h = 1, Smith Lambda for the height-correlated masking-
// shadowing G2 = 1 / (1 + Lambda(wi) + Lambda(wo)). Local frame, z = macro normal.
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
    explicit GgxDistribution(double alpha) : alpha_(alpha) {}
    double alpha() const { return alpha_; }
    double D(const Vec3& h) const;
    double lambda(const Vec3& w) const;
    double G1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
    double G2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
    // Visible normals seen from w (Heitz 2018): density D_w(h) = G1(w) max(0, w.h) D(h) / cos(theta_w).
    double visible_density(const Vec3& w, const Vec3& h) const;
    Vec3 sample_visible(const Vec3& w, Vec2 u) const;

private:
    double alpha_;
};

// Beckmann with alpha = rms slope (THEORY 4.2); sampled by D(h) cos(theta_h) (no closed-form visible sampler).
class BeckmannDistribution {
public:
    explicit BeckmannDistribution(double alpha) : alpha_(alpha) {}
    double alpha() const { return alpha_; }
    double D(const Vec3& h) const;
    double lambda(const Vec3& w) const;
    double G2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
    // Density D(h) cos(theta_h) over the hemisphere of normals, and its sampler.
    double projected_density(const Vec3& h) const { return D(h) * h.z; }
    Vec3 sample_projected(Vec2 u) const;

private:
    double alpha_;
};

// Solid-angle density of wo = reflect(wi, h) given the density of h: p(wo) = p(h) / (4 |wo.h|).
inline double reflection_jacobian(const Vec3& wo, const Vec3& h) { return 1.0 / (4.0 * std::abs(dot(wo, h))); }
inline Vec3 reflect(const Vec3& w, const Vec3& h) { return 2.0 * dot(w, h) * h - w; }

}  // namespace surfscatter::bsdf
