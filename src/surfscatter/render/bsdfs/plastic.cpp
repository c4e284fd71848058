// Mitsuba's `plastic` BSDF: a smooth dielectric coating over a diffuse base (delta specular reflection plus a
// diffuse lobe of light that crossed the coating twice).
//
// Supported: `diffuse_reflectance` (default 0.5), `specular_reflectance` (default 1), `int_ior` (default
// polypropylene, 1.49), `ext_ior` (default air), `nonlinear` (default false). With F the Fresnel reflectance and
// eta = int_ior / ext_ior: the delta lobe reflects F(cos_o) x specular_reflectance; the diffuse lobe is
// f = rho / (1 - Fdr) (1 - F(cos_i)) (1 - F(cos_o)) / (pi eta^2), with Fdr the hemispherical reflectance of the
// coating from inside (material/fresnel.hpp, exact quadrature), or rho / (1 - rho Fdr) with nonlinear = true (the
// colour shift of internal scattering). Its albedo is then (1 - F(cos_o)) rho (linear) or
// (1 - F(cos_o)) rho (1 - Fdr) / (1 - rho Fdr) (nonlinear), tests/render/test_bsdfs.cpp. One-sided.
// Sampling: the delta lobe with probability F w / (F w + (1 - F)(1 - w)), w = s / (s + d) from the scalar values
// (eval_1) of the two reflectances at the shading point, else the cosine-weighted diffuse lobe.
// Differences: Mitsuba approximates Fdr by a polynomial fit and weighs the lobes by the textures' means.
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class SmoothPlastic final : public Material {
public:
    SmoothPlastic(double eta, TexturePtr diffuse, TexturePtr specular, bool nonlinear)
        : eta_(eta), fdr_inside_(material::fresnel_diffuse_reflectance(1 / eta)), diffuse_(std::move(diffuse)),
          specular_(std::move(specular)), nonlinear_(nonlinear) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (pdf) *pdf = SampledSpectrum(0.0);
        if (wi.z <= 0 || wo.z <= 0) return SampledSpectrum(0.0);
        const double f_o = fresnel(wo.z);
        if (pdf) *pdf = SampledSpectrum((1 - specular_probability(sp, f_o)) * wi.z * kInvPi);
        return diffuse_lobe(sp, w) * ((1 - f_o) * (1 - fresnel(wi.z)) * kInvPi / (eta_ * eta_));
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        const double f_o = fresnel(wo.z);
        const double p_specular = specular_probability(sp, f_o);
        MaterialSample s;
        if (u_lobe < p_specular) {
            s.delta = true;
            s.wi = reflect_about_normal(wo);
            s.f = specular_->eval(sp.uv, w) * f_o;
            s.pdf = SampledSpectrum(p_specular);
            return s;
        }
        s.wi = square_to_cosine_hemisphere(u);
        if (s.wi.z <= 0) return std::nullopt;
        s.f = eval(sp, s.wi, wo, w, &s.pdf);
        return s;
    }

private:
    double fresnel(double cos_theta) const { return material::fresnel_dielectric(cos_theta, eta_).reflectance; }

    double specular_probability(const ShadingPoint& sp, double f_o) const {
        const double s = specular_->eval_1(sp.uv), d = diffuse_->eval_1(sp.uv);
        const double weight = s + d > 0 ? s / (s + d) : 0.5;
        const double a = f_o * weight, b = (1 - f_o) * (1 - weight);
        return a + b > 0 ? a / (a + b) : 0.0;
    }

    // rho / (1 - Fdr) or rho / (1 - rho Fdr).
    SampledSpectrum diffuse_lobe(const ShadingPoint& sp, const SampledWavelengths& w) const {
        SampledSpectrum rho = diffuse_->eval(sp.uv, w);
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) rho[i] /= 1 - (nonlinear_ ? rho[i] : 1.0) * fdr_inside_;
        return rho;
    }

    double eta_, fdr_inside_;
    TexturePtr diffuse_, specular_;
    bool nonlinear_;
};

}  // namespace

MaterialPtr plugins::plastic(Properties& props) {
    const double eta = read_relative_ior(props, "polypropylene", "air", false);
    return std::make_shared<SmoothPlastic>(eta, props.get_texture("diffuse_reflectance", 0.5),
                                           props.get_texture("specular_reflectance", 1.0), props.get_bool("nonlinear", false));
}

}  // namespace surfscatter::render
