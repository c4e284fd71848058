#include "surfscatter/bsdf/ggx.hpp"

#include <cmath>

#include "surfscatter/bsdf/microfacet.hpp"

namespace surfscatter::bsdf {

GgxBsdf::GgxBsdf(material::Conductor material, std::function<double(double)> alpha)
    : material_(std::move(material)), alpha_(std::move(alpha)) {}

GgxBsdf::GgxBsdf(material::Conductor material, double alpha)
    : GgxBsdf(std::move(material), [alpha](double) { return alpha; }) {}

double GgxBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const GgxDistribution ggx(alpha_(lambda_nm));
    const double F = material_.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
    return ggx.D(h) * ggx.G2(wi, wo) * F / (4.0 * wi.z * wo.z);
}

double GgxBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const GgxDistribution ggx(alpha_(lambda_nm));
    return ggx.visible_density(wi, h) * reflection_jacobian(wo, h);
}

std::optional<BsdfSample> GgxBsdf::sample(const Vec3& wi, double lambda_nm, double /*u_lobe*/, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const GgxDistribution ggx(alpha_(lambda_nm));
    const Vec3 h = ggx.sample_visible(wi, u);
    const Vec3 wo = reflect(wi, h);
    if (wo.z <= 0) return std::nullopt;
    const double p = ggx.visible_density(wi, h) * reflection_jacobian(wo, h);
    if (!(p > 0) || !std::isfinite(p)) return std::nullopt;
    // f cos / pdf = F G2 / G1(wi), independent of D.
    const double F = material_.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
    BsdfSample s;
    s.wo = wo;
    s.pdf = p;
    s.weight = F * ggx.G2(wi, wo) / ggx.G1(wi);
    return s;
}

double kc_link_alpha(double corr_length_um, double lambda_nm) {
    const double k = kTwoPi / (lambda_nm * 1e-3);  // rad/um
    return 1.0 / std::sqrt(1.0 + 4.0 * k * k * corr_length_um * corr_length_um);
}

}  // namespace surfscatter::bsdf
