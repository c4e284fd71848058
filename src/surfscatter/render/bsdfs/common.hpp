#pragma once
// What several BSDF plugins share: indices of refraction by value or by Mitsuba's names, a conductor's complex
// index tabulated over the sampled wavelengths, the microfacet distributions of the rough plugins and the two delta
// lobes of the smooth dielectrics.
#include <algorithm>
#include <complex>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/render/properties.hpp"
#include "surfscatter/spectrum/wavelength_sampling.hpp"

namespace surfscatter::render {

// int_ior or ext_ior: a <float>, or one of Mitsuba's named indices (Hecht, Optics, 4th ed., at 589 nm: vacuum 1,
// helium 1.000036, hydrogen 1.000132, air 1.000277, carbon dioxide 1.00045, water 1.333, acetone 1.36, ethanol 1.361,
// carbon tetrachloride 1.461, glycerol 1.4729, benzene 1.501, silicone oil 1.52045, bromine 1.661, water ice 1.31,
// fused quartz 1.458, pyrex 1.47, acrylic glass 1.49, polypropylene 1.49, bk7 1.5046, sodium chloride 1.544, amber
// 1.55, pet 1.575, diamond 2.419); `fallback` names the default.
double read_ior(Properties& props, const std::string& name, const std::string& fallback);
// eta = int_ior / ext_ior, checked to be positive and (if `must_differ`) not 1.
double read_relative_ior(Properties& props, const std::string& int_default, const std::string& ext_default,
                         bool must_differ);

// The complex index n + ik of a conductor at 1 nm steps over 360-830 nm (the Lorentz-Drude and tabulated models are
// costly per call), or the perfect mirror.
class ConductorIor {
public:
    ConductorIor() = default;  // perfect mirror
    explicit ConductorIor(const std::function<std::complex<double>(double)>& index);
    bool perfect() const { return table_.empty(); }
    // Inline: reflectance reads it four times per call, on every conductor vertex of every path.
    std::complex<double> at(double lambda_nm) const {
        const double x = std::clamp(lambda_nm - spectrum::kSampledLambdaMin, 0.0, static_cast<double>(kTableSize - 1));
        const int i = std::min(static_cast<int>(x), kTableSize - 2);
        const double t = x - i;
        return table_[static_cast<std::size_t>(i)] * (1 - t) + table_[static_cast<std::size_t>(i + 1)] * t;
    }
    // Unpolarised Fresnel reflectance at the four wavelengths of a path (1 for the perfect mirror); cos_theta is
    // clamped to [0, 1]. Computed in single precision, the four wavelengths in one SSE lane set: within 1e-6 of the
    // double-precision reflectance (tests/render/test_bsdfs.cpp), far below any render's noise.
    SampledSpectrum reflectance(double cos_theta, const SampledWavelengths& w) const;

private:
    static constexpr int kTableSize =
        static_cast<int>(spectrum::kSampledLambdaMax - spectrum::kSampledLambdaMin) + 1;
    std::vector<std::complex<double>> table_;
};
// conductor / roughconductor: `material` (Mitsuba's name for a built-in metal, `none` = perfect mirror, or a
// refractiveindex.info .yml / wavelength_nm,n,k .csv path), or `eta` and `k` spectra (defaults 0 and 1 = mirror).
ConductorIor read_conductor_ior(Properties& props);

// Mitsuba's microfacet distributions for roughconductor, roughdielectric and roughplastic: `distribution` beckmann
// (Mitsuba's default) or ggx, `alpha`, or `alpha_u` along the shading frame's s = dp/du and `alpha_v` along t
// (anisotropic: bsdf/microfacet.hpp's forms; roughplastic, like Mitsuba's, takes alpha_u = alpha_v only), Smith's
// separable shadowing-masking G = G1(wi) G1(wo) as Mitsuba. Normals are sampled from the visible normals (GGX with
// sample_visible, Heitz 2018) or from D(m) cos(theta_m) (Beckmann, or sample_visible = false).
class Microfacet {
public:
    Microfacet(bool beckmann, double alpha_u, double alpha_v, bool sample_visible);
    // distribution, alpha / alpha_u / alpha_v, sample_visible; alpha_u != alpha_v is an error unless `anisotropic`.
    static Microfacet read(Properties& props, bool anisotropic = true);
    double D(const Vec3& m) const;
    double G1(const Vec3& w, const Vec3& m) const;  // 0 unless w and m are on the same side of the facet
    double G(const Vec3& wi, const Vec3& wo, const Vec3& m) const { return G1(wi, m) * G1(wo, m); }
    // A normal (upper hemisphere) seen from w (w.z > 0), and its density.
    Vec3 sample(const Vec3& w, Vec2 u) const;
    double pdf(const Vec3& w, const Vec3& m) const;
    // A normal distributed as D(m) cos(theta_m) (density D(m) m.z), whatever sample_visible says.
    Vec3 sample_projected(Vec2 u) const;
    // Directional albedo of microfacet reflection, int F(wo.m) D G / (4 cos_i cos_o) cos_i dwi, for a dielectric
    // of index ratio eta seen from wo (wo.z > 0); quadrature over the projected normals (24 x 24 Gauss-Legendre).
    double reflection_albedo(const Vec3& wo, double eta) const;

private:
    double lambda(const Vec3& w) const;
    bool beckmann_;
    bool visible_;
    bsdf::GgxDistribution ggx_;
    bsdf::BeckmannDistribution beckmann_distribution_;
};

// Mirror reflection about m and refraction through m (Mitsuba's reflect / refract; eta_ti as from
// fresnel_dielectric for the cosine of w with m).
inline Vec3 reflect(const Vec3& w, const Vec3& m) { return 2 * dot(w, m) * m - w; }
inline Vec3 refract(const Vec3& w, const Vec3& m, double cos_theta_t, double eta_ti) {
    return m * (dot(w, m) * eta_ti + cos_theta_t) - w * eta_ti;
}

// A smooth dielectric's two delta lobes (dielectric, thindielectric): `int_ior`/`ext_ior`, `specular_reflectance`,
// `specular_transmittance`. The subclass gives, for wo, the probability r of reflection about the normal and the
// transmitted direction with its weight; both lobes are chosen with their probabilities.
class SmoothDielectricLobes : public DeltaMaterial {
public:
    explicit SmoothDielectricLobes(Properties& props);
    bool has_transmission() const final { return true; }

protected:
    // Reflection with probability r (weight r times specular_reflectance), else transmission along wi_transmitted
    // (weight (1 - r) * transmitted_scale times specular_transmittance).
    MaterialSample choose_lobe(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                               double r, const Vec3& wi_transmitted, double transmitted_scale) const;
    double eta_;  // int_ior / ext_ior

private:
    TexturePtr reflectance_, transmittance_;
};

}  // namespace surfscatter::render
