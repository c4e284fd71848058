// Mitsuba's `roughplastic` BSDF: a rough dielectric coating (microfacet reflection) over a diffuse base.
//
// Supported: `distribution` (beckmann (default) | ggx), `alpha` (default 0.1; or alpha_u = alpha_v),
// `sample_visible` (default true; honoured for ggx), `diffuse_reflectance` (default 0.5), `specular_reflectance`
// (default 1), `int_ior` (default polypropylene), `ext_ior` (default air), `nonlinear` (default false).
// f = specular_reflectance F(wo.m) D G / (4 cos_i cos_o) + rho / (1 - Fint) T(cos_i) T(cos_o) / (pi eta^2), as
// Mitsuba: T(mu) = 1 - (directional albedo of the microfacet reflection at mu) on a 64-point table, Fint the
// hemispherical average of that albedo from inside (index ratio 1/eta); rho / (1 - rho Fint) with nonlinear.
// The tables are computed when the BSDF is built (quadrature over the projected normals). One-sided.
// Sampling: the specular lobe with probability (1 - T(cos_o)) w / ((1 - T) w + T (1 - w)), w = s / (s + d) from
// the scalar values of the reflectances at the shading point, else the cosine-weighted diffuse lobe.
// Not supported (an error): anisotropic alpha (alpha_u != alpha_v: T(mu) is tabulated over cos only, and Mitsuba's
// roughplastic takes one alpha too), textured alpha.
// Differences: the lobe weights use the reflectances at the shading point (Mitsuba: the textures' means);
// Beckmann normals are sampled from D cos.
#include <algorithm>

#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

constexpr int kTable = 64;

class RoughPlastic final : public Material {
public:
    RoughPlastic(double eta, Microfacet distribution, TexturePtr diffuse, TexturePtr specular, bool nonlinear)
        : eta_(eta), distribution_(distribution), diffuse_(std::move(diffuse)), specular_(std::move(specular)),
          nonlinear_(nonlinear) {
        for (int i = 0; i < kTable; ++i) {
            const double mu = std::max(1e-6, static_cast<double>(i) / (kTable - 1));
            transmittance_[static_cast<std::size_t>(i)] =
                1 - distribution_.reflection_albedo({std::sqrt(1 - mu * mu), 0, mu}, eta_);
        }
        // Hemispherical average 2 int_0^1 R(mu) mu dmu from inside; the albedo changes quickly around the critical
        // cosine of total internal reflection, so each side of it gets its own Gauss-Legendre rule.
        std::vector<double> nodes, weights;
        math::gauss_legendre(48, nodes, weights);
        const double critical = eta_ > 1 ? std::sqrt(1 - 1 / (eta_ * eta_)) : 0.0;
        double inside = 0;
        for (const auto& [a, b] : {std::pair{0.0, critical}, std::pair{critical, 1.0}}) {
            for (std::size_t k = 0; k < nodes.size() && b > a; ++k) {
                const double mu = 0.5 * (a + b) + 0.5 * (b - a) * nodes[k];
                inside += weights[k] * (b - a) * distribution_.reflection_albedo({std::sqrt(1 - mu * mu), 0, mu}, 1 / eta_) * mu;
            }
        }
        internal_reflectance_ = inside;
    }

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (pdf) *pdf = SampledSpectrum(0.0);
        if (wi.z <= 0 || wo.z <= 0) return SampledSpectrum(0.0);
        const Vec3 m = normalize(wi + wo);
        const double t_o = transmittance(wo.z), t_i = transmittance(wi.z);
        const double specular = material::fresnel_dielectric(dot(wo, m), eta_).reflectance * distribution_.D(m) *
                                distribution_.G(wi, wo, m) / (4 * wi.z * wo.z);
        SampledSpectrum rho = diffuse_->eval(sp.uv, w);
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            rho[i] = rho[i] / (1 - (nonlinear_ ? rho[i] : 1.0) * internal_reflectance_) * t_i * t_o * kInvPi / (eta_ * eta_);
        if (pdf) {
            const double p_specular = specular_probability(sp, t_o);
            const double wo_m = dot(wo, m);
            const double p_glossy = wo_m > 0 ? distribution_.pdf(wo, m) / (4 * wo_m) : 0.0;
            *pdf = SampledSpectrum(p_specular * p_glossy + (1 - p_specular) * wi.z * kInvPi);
        }
        return specular_->eval(sp.uv, w) * specular + rho;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = u_lobe < specular_probability(sp, transmittance(wo.z)) ? reflect(wo, distribution_.sample(wo, u))
                                                                        : square_to_cosine_hemisphere(u);
        if (s.wi.z <= 0) return std::nullopt;
        s.f = eval(sp, s.wi, wo, w, &s.pdf);
        if (!(s.pdf[0] > 0)) return std::nullopt;
        return s;
    }

private:
    double transmittance(double mu) const {
        const double x = std::clamp(mu, 0.0, 1.0) * (kTable - 1);
        const int i = std::min(static_cast<int>(x), kTable - 2);
        const double t = x - i;
        return transmittance_[static_cast<std::size_t>(i)] * (1 - t) + transmittance_[static_cast<std::size_t>(i) + 1] * t;
    }

    double specular_probability(const ShadingPoint& sp, double t_o) const {
        const double s = specular_->eval_1(sp.uv), d = diffuse_->eval_1(sp.uv);
        const double weight = s + d > 0 ? s / (s + d) : 0.5;
        const double a = (1 - t_o) * weight, b = t_o * (1 - weight);
        return a + b > 0 ? a / (a + b) : 0.0;
    }

    double eta_;
    Microfacet distribution_;
    TexturePtr diffuse_, specular_;
    bool nonlinear_;
    std::array<double, kTable> transmittance_{};
    double internal_reflectance_ = 0;
};

}  // namespace

MaterialPtr plugins::roughplastic(Properties& props) {
    const double eta = read_relative_ior(props, "polypropylene", "air", true);
    const Microfacet distribution = Microfacet::read(props, false);  // T(mu) tables: isotropic only, as Mitsuba's
    return std::make_shared<RoughPlastic>(eta, distribution, props.get_texture("diffuse_reflectance", 0.5),
                                          props.get_texture("specular_reflectance", 1.0), props.get_bool("nonlinear", false));
}

}  // namespace surfscatter::render
