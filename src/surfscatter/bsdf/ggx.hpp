#pragma once
// GGX (Trowbridge-Reitz) microfacet conductor: height-correlated Smith masking-shadowing, visible-normal sampling
// (Heitz 2018), exact conductor Fresnel at the microfacet normal. The roughness may depend on the wavelength
// (alpha_from = kc_link, THEORY 4.3), so it is a function of lambda. Anisotropic: alpha_u along the lay direction u,
// alpha_v across it, the lay at angle A from x towards y (surface::EllipticalStatistics' convention); directions are
// rotated into the (u, v) frame and evaluated with the axis-aligned anisotropic GgxDistribution (microfacet.hpp).
#include <functional>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

class GgxBsdf final : public Bsdf {
public:
    GgxBsdf(material::Conductor material, std::function<double(double lambda_nm)> alpha);
    GgxBsdf(material::Conductor material, double alpha);
    // Anisotropic: alpha_u and alpha_v at a wavelength, and the lay angle A in radians.
    GgxBsdf(material::Conductor material, std::function<double(double lambda_nm)> alpha_u,
            std::function<double(double lambda_nm)> alpha_v, double lay_angle_rad);
    GgxBsdf(material::Conductor material, Vec2 alpha_uv, double lay_angle_rad);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    // The half vector, and D, G2 and the density when alpha does not depend on lambda, once for all wavelengths.
    WavelengthValues eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                 WavelengthValues* pdf) const override;
    std::string name() const override { return "ggx_stats"; }  // the model's one name (model_options)
    // The anisotropic one (alpha_v given) depends on the azimuths through the lay: its albedo on phi_i (albedo.hpp).
    bool isotropic() const override { return !alpha_v_; }

    double alpha(double lambda_nm) const { return alpha_(lambda_nm); }  // alpha_u
    Vec2 alpha_uv(double lambda_nm) const;
    double lay_angle() const { return lay_.angle(); }  // radians

private:
    // eval, pdf and eval_packet of directions in the lay frame (upper hemisphere).
    double eval_lay(const Vec3& wi, const Vec3& wo, double lambda_nm) const;
    double pdf_lay(const Vec3& wi, const Vec3& wo, double lambda_nm) const;
    WavelengthValues eval_packet_lay(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                     WavelengthValues* pdf) const;
    // alpha_ is alpha_u (or the isotropic alpha), alpha_v_ empty when isotropic. One double per function: a (u, v)
    // pair returned through std::function cost GGX eval a store-forwarding stall (2.5x its time).
    GgxDistribution distribution(double lambda_nm) const {
        if (!alpha_v_) return GgxDistribution(alpha_(lambda_nm));
        return GgxDistribution(alpha_(lambda_nm), alpha_v_(lambda_nm));
    }

    material::Conductor material_;
    std::function<double(double)> alpha_, alpha_v_;
    bool alpha_constant_ = false;
    LayFrame lay_;
};

// GGX roughness of the KC(gamma = 3) first-order lobe at normal incidence (THEORY 4.3 with cos(theta_d) = 1):
// alpha^2 = 1 / (1 + 4 k^2 L^2), k = 2 pi / lambda; L and lambda in the same unit. For an elliptical KC(3) surface
// the lobe k^2 P-hat(2 k h_xy) ~ (h_z^2 + (1 + 4 k^2 LU^2) h_u^2 + (1 + 4 k^2 LV^2) h_v^2)^-2 is the anisotropic GGX
// with alpha_u = kc_link_alpha(LU), alpha_v = kc_link_alpha(LV) exactly (docs/MODELS.md).
double kc_link_alpha(double corr_length_um, double lambda_nm);

}  // namespace surfscatter::bsdf
