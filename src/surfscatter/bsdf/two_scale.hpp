#pragma once
// Two-scale model with the structure of Holzschuch & Pacanowski 2017 (THEORY 3):
//   f_r = e^{-g0,micro} F(theta_d) D(h) G2(i, o) / (4 cos theta_i cos theta_o)     macro (microfacet) part
//       + f_GHS,micro(i, o)                                                        micro (diffraction) part
// where the PSD is split at zeta_c = k_ref / N (psd_split.hpp, sharp low-pass, exact statistics of both parts in
// sharp_cut.hpp): D is a GGX or Beckmann NDF with alpha = rms slope of the low-pass part, f_GHS,micro the full GHS
// scattered lobe (exact S_g, K renormalised) of the high-pass part, and e^{-g0,micro} = exp(-(2 k sigma_rel,micro
// cos theta_i)^2) the fraction of light the micro roughness leaves specular: the micro GHS's coherent delta is what the
// macro facets spread out, so there is no delta left. HP17 evaluate this fraction at the facet angle theta_d
// (A_s(theta_d)); we use theta_i, so that the micro part carries exactly R (1 - e^{-g0}) and the macro part e^{-g0}
// times its microfacet albedo, which shadowing keeps below the facets' mean F(theta_d): for a perfect conductor the
// albedo is at most R = 1 (for a metal whose F(theta_d) exceeds R(theta_i) it can exceed R slightly; docs/MODELS.md
// gives the measured bounds, tests/bsdf/test_albedo.cpp).
// Approximations (documented in docs/MODELS.md): the micro lobe is NOT convolved with the macro NDF (HP17's "Dirac"
// case); the split uses the reference wavelength 550 nm for every query so that the macro NDF and micro statistics
// are wavelength-independent (the micro lobe itself is evaluated at the query wavelength).
// Sampling: the macro lobe with probability e^{-g0,micro} (the micro GHS's delta probability), else the micro GHS
// sampler; the pdf is the exact mixture.
// The macro NDF may be anisotropic (alpha_u along the lay direction at lay_angle, alpha_v across; microfacet.hpp), and
// the micro lobe is any Bsdf whose delta_probability() is e^{-g0,micro} (the GHS of the high-pass part, isotropic or
// not): only its Bsdf interface is used. On elliptical statistics (the factory; docs/MODELS.md "Two-scale on elliptical
// statistics") the macro weight depends on the incidence azimuth: it is the micro lobe's at the local-frame incidence.
// Without a micro lobe (null: a height map that resolves no roughness finer than zeta_c) the model is the macro
// microfacet lobe alone, of weight 1.
#include <memory>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/material/conductor.hpp"

namespace surfscatter::bsdf {

class TwoScaleBsdf final : public Bsdf {
public:
    TwoScaleBsdf(material::Conductor material, MacroNdf ndf, double macro_alpha, std::unique_ptr<Bsdf> micro);
    // Anisotropic macro NDF: (alpha_u, alpha_v) and the lay angle in radians.
    TwoScaleBsdf(material::Conductor material, MacroNdf ndf, Vec2 macro_alpha_uv, double lay_angle_rad,
                 std::unique_ptr<Bsdf> micro);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    double jump_radius(double lambda_nm) const override { return micro_ ? micro_->jump_radius(lambda_nm) : 0.0; }
    std::string name() const override { return "two_scale"; }
    bool isotropic() const override { return alpha_.x == alpha_.y && (!micro_ || micro_->isotropic()); }

    double macro_alpha() const { return alpha_.x; }  // alpha_u
    Vec2 macro_alpha_uv() const { return alpha_; }
    bool has_micro() const { return micro_ != nullptr; }
    const Bsdf& micro() const { return *micro_; }  // has_micro() only

private:
    // Both in the lay frame.
    // weight: the micro lobe's delta probability e^{-g0,micro} at the incidence in the local frame.
    double macro_eval(const Vec3& wi, const Vec3& wo, double lambda_nm, double weight) const;
    double macro_pdf(const Vec3& wi, const Vec3& wo) const;  // density of the macro sampler alone
    // e^{-g0,micro}: the micro lobe's delta probability, 1 without one.
    double macro_weight(const Vec3& wi, double lambda_nm) const {
        return micro_ ? micro_->delta_probability(wi, lambda_nm) : 1.0;
    }

    material::Conductor material_;
    MacroNdf ndf_;
    Vec2 alpha_;
    LayFrame lay_;
    GgxDistribution ggx_;
    BeckmannDistribution beckmann_;
    std::unique_ptr<Bsdf> micro_;
};

// Reference wavelength of the macro/micro split (nm).
inline constexpr double kTwoScaleReferenceWavelength = 550.0;

}  // namespace surfscatter::bsdf
