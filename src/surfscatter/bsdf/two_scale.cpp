#include "surfscatter/bsdf/two_scale.hpp"

#include <cmath>

#include "surfscatter/bsdf/microfacet.hpp"

namespace surfscatter::bsdf {

TwoScaleBsdf::TwoScaleBsdf(material::Conductor material, MacroNdf ndf, double macro_alpha, std::unique_ptr<Bsdf> micro)
    : TwoScaleBsdf(std::move(material), ndf, Vec2(macro_alpha, macro_alpha), 0.0, std::move(micro)) {}

TwoScaleBsdf::TwoScaleBsdf(material::Conductor material, MacroNdf ndf, Vec2 macro_alpha_uv, double lay_angle_rad,
                           std::unique_ptr<Bsdf> micro)
    : material_(std::move(material)), ndf_(ndf), alpha_(macro_alpha_uv), lay_(lay_angle_rad),
      ggx_(macro_alpha_uv.x, macro_alpha_uv.y), beckmann_(macro_alpha_uv.x, macro_alpha_uv.y), micro_(std::move(micro)) {}

double TwoScaleBsdf::macro_eval(const Vec3& wi, const Vec3& wo, double lambda_nm, double weight) const {
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const double cos_d = std::clamp(dot(wi, h), 0.0, 1.0);
    const double specular = weight * material_.reflectance(cos_d, lambda_nm);
    const double dg = ndf_ == MacroNdf::ggx ? ggx_.D(h) * ggx_.G2(wi, wo) : beckmann_.D(h) * beckmann_.G2(wi, wo);
    return specular * dg / (4.0 * wi.z * wo.z);
}

double TwoScaleBsdf::macro_pdf(const Vec3& wi, const Vec3& wo) const {
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const double ph = ndf_ == MacroNdf::ggx ? ggx_.visible_density(wi, h) : beckmann_.projected_density(h);
    return ph * reflection_jacobian(wo, h);
}

double TwoScaleBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    // The macro weight from the micro lobe at the local-frame incidence (an anisotropic micro lobe's depends on it).
    const double f = macro_eval(lay_.to_lay(wi), lay_.to_lay(wo), lambda_nm, macro_weight(wi, lambda_nm)) +
                     (micro_ ? micro_->eval(wi, wo, lambda_nm) : 0.0);
    return std::isfinite(f) ? f : 0.0;
}

double TwoScaleBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double p = macro_weight(wi, lambda_nm) * macro_pdf(lay_.to_lay(wi), lay_.to_lay(wo)) +
                     (micro_ ? micro_->pdf(wi, wo, lambda_nm) : 0.0);
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> TwoScaleBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    Vec3 wo;
    if (!micro_ || u_lobe < macro_weight(wi, lambda_nm)) {
        const Vec3 wi_lay = lay_.to_lay(wi);
        const Vec3 h = ndf_ == MacroNdf::ggx ? ggx_.sample_visible(wi_lay, u) : beckmann_.sample_projected(u);
        wo = lay_.from_lay(reflect(wi_lay, h));
    } else {
        const auto s = micro_->sample(wi, lambda_nm, u_lobe, u);  // u_lobe above the delta probability: scatter
        if (!s) return std::nullopt;
        wo = s->wo;
    }
    if (wo.z <= 0) return std::nullopt;
    BsdfSample out;
    out.wo = wo;
    out.pdf = pdf(wi, wo, lambda_nm);
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    out.weight = eval(wi, wo, lambda_nm) * wo.z / out.pdf;
    if (!std::isfinite(out.weight)) return std::nullopt;
    return out;
}

}  // namespace surfscatter::bsdf
