#pragma once
// GGX (Trowbridge-Reitz) microfacet conductor: height-correlated Smith masking-shadowing, visible-normal sampling
// (Heitz 2018), exact conductor Fresnel at the microfacet normal. The roughness may depend on the wavelength
// (alpha_from = kc_link, THEORY 4.3), so it is a function of lambda.
#include <functional>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/material/conductor.hpp"

namespace surfscatter::bsdf {

class GgxBsdf final : public Bsdf {
public:
    GgxBsdf(material::Conductor material, std::function<double(double lambda_nm)> alpha);
    GgxBsdf(material::Conductor material, double alpha);

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    // The half vector, and D, G2 and the density when alpha does not depend on lambda, once for all wavelengths.
    WavelengthValues eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                 WavelengthValues* pdf) const override;
    std::string name() const override { return "ggx_stats"; }  // the model's one name (model_options)

    double alpha(double lambda_nm) const { return alpha_(lambda_nm); }

private:
    material::Conductor material_;
    std::function<double(double)> alpha_;
    bool alpha_constant_ = false;
};

// GGX roughness of the KC(gamma = 3) first-order lobe at normal incidence (THEORY 4.3 with cos(theta_d) = 1):
// alpha^2 = 1 / (1 + 4 k^2 L^2), k = 2 pi / lambda; L and lambda in the same unit.
double kc_link_alpha(double corr_length_um, double lambda_nm);

}  // namespace surfscatter::bsdf
