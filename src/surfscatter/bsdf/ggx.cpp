#include "surfscatter/bsdf/ggx.hpp"

#include <cmath>

#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

GgxBsdf::GgxBsdf(material::Conductor material, std::function<double(double)> alpha)
    : material_(std::move(material)), alpha_(std::move(alpha)) {}

GgxBsdf::GgxBsdf(material::Conductor material, double alpha)
    : GgxBsdf(std::move(material), [alpha](double) { return alpha; }) {
    alpha_constant_ = true;
}

GgxBsdf::GgxBsdf(material::Conductor material, std::function<double(double)> alpha_u,
                 std::function<double(double)> alpha_v, double lay_angle_rad)
    : material_(std::move(material)), alpha_(std::move(alpha_u)), alpha_v_(std::move(alpha_v)), lay_(lay_angle_rad) {}

GgxBsdf::GgxBsdf(material::Conductor material, Vec2 alpha_uv, double lay_angle_rad)
    : GgxBsdf(std::move(material), [u = alpha_uv.x](double) { return u; }, [v = alpha_uv.y](double) { return v; },
              lay_angle_rad) {
    alpha_constant_ = true;
}

Vec2 GgxBsdf::alpha_uv(double lambda_nm) const {
    const double u = alpha_(lambda_nm);
    return {u, alpha_v_ ? alpha_v_(lambda_nm) : u};
}

double GgxBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return lay_.turned() ? eval_lay(lay_.to_lay(wi), lay_.to_lay(wo), lambda_nm) : eval_lay(wi, wo, lambda_nm);
}

// Inlined into eval and pdf: as calls they cost isotropic GGX eval and pdf 1-2 ns (of 13-15) against the code
// before anisotropy (docs/PERFORMANCE.md).
[[gnu::always_inline]] inline double GgxBsdf::eval_lay(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const GgxDistribution ggx = distribution(lambda_nm);
    const double F = material_.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
    return ggx.D(h) * ggx.G2(wi, wo) * F / (4.0 * wi.z * wo.z);
}

double GgxBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return lay_.turned() ? pdf_lay(lay_.to_lay(wi), lay_.to_lay(wo), lambda_nm) : pdf_lay(wi, wo, lambda_nm);
}

[[gnu::always_inline]] inline double GgxBsdf::pdf_lay(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return 0.0;
    const Vec3 h = normalize(sum);
    const GgxDistribution ggx = distribution(lambda_nm);
    return ggx.visible_density(wi, h) * reflection_jacobian(wo, h);
}

WavelengthValues GgxBsdf::eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                      WavelengthValues* pdf) const {
    if (wi.z <= 0 || wo.z <= 0) {
        if (pdf) pdf->fill(0.0);
        return WavelengthValues{};
    }
    return lay_.turned() ? eval_packet_lay(lay_.to_lay(wi), lay_.to_lay(wo), lambda_nm, pdf)
                         : eval_packet_lay(wi, wo, lambda_nm, pdf);
}

WavelengthValues GgxBsdf::eval_packet_lay(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                          WavelengthValues* pdf) const {
    WavelengthValues f{};
    if (pdf) pdf->fill(0.0);
    const Vec3 sum = wi + wo;
    if (sum.length_squared() == 0) return f;
    const Vec3 h = normalize(sum);
    const double cos_d = std::clamp(dot(wi, h), 0.0, 1.0);
    double d_g = 0, density = 0;  // D G2 / (4 cos_i cos_o) and pdf(wo, wi) for one alpha
    const auto geometry = [&](double lambda) {
        const GgxDistribution ggx = distribution(lambda);
        d_g = ggx.D(h) * ggx.G2(wi, wo) / (4.0 * wi.z * wo.z);
        if (pdf) density = ggx.visible_density(wo, h) * reflection_jacobian(wi, h);
    };
    if (alpha_constant_) geometry(lambda_nm[0]);
    for (std::size_t k = 0; k < f.size(); ++k) {
        if (!alpha_constant_) geometry(lambda_nm[k]);
        f[k] = d_g * material_.reflectance(cos_d, lambda_nm[k]);
        if (pdf) (*pdf)[k] = density;
    }
    return f;
}

std::optional<BsdfSample> GgxBsdf::sample(const Vec3& wi_local, double lambda_nm, double /*u_lobe*/, Vec2 u) const {
    if (wi_local.z <= 0) return std::nullopt;
    const Vec3 wi = lay_.to_lay(wi_local);
    const GgxDistribution ggx = distribution(lambda_nm);
    const Vec3 h = ggx.sample_visible(wi, u);
    const Vec3 wo = reflect(wi, h);
    if (wo.z <= 0) return std::nullopt;
    const double p = ggx.visible_density(wi, h) * reflection_jacobian(wo, h);
    if (!(p > 0) || !std::isfinite(p)) return std::nullopt;
    // f cos / pdf = F G2 / G1(wi), independent of D.
    const double F = material_.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
    BsdfSample s;
    s.wo = lay_.from_lay(wo);
    s.pdf = p;
    s.weight = F * ggx.G2(wi, wo) / ggx.G1(wi);
    return s;
}

double kc_link_alpha(double corr_length_um, double lambda_nm) {
    const double k = kTwoPi / (lambda_nm * 1e-3);  // rad/um
    const double alpha = 1.0 / std::sqrt(1.0 + 4.0 * k * k * corr_length_um * corr_length_um);
    // At wavelengths far below L (1e-100 nm: k^2 overflows, alpha 0) GGX is not defined: refused, not NaN.
    if (!(alpha >= kMinMicrofacetAlpha))
        fail("alpha_from kc_link gives alpha = {} at wavelength {} nm (correlation length {} um), below GGX's {}", alpha,
             lambda_nm, corr_length_um, kMinMicrofacetAlpha);
    return alpha;
}

}  // namespace surfscatter::bsdf
