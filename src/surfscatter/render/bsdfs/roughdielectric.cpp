// Mitsuba's `roughdielectric` BSDF: a rough interface between two dielectrics (Walter et al. 2007).
//
// Supported: `int_ior` (default bk7), `ext_ior` (default air), `distribution` (beckmann (default) | ggx), `alpha`
// (default 0.1; or alpha_u along s = dp/du and alpha_v along t, anisotropic), `sample_visible` (default true; honoured for ggx), `specular_reflectance`,
// `specular_transmittance` (default 1). With viewer wo, light wi and eta the index ratio across the interface from
// the viewer's side: reflection F D G / (4 |cos_i cos_o|) at m = normalize(wi + wo); refraction
// (1 - F) D G |wi.m| |wo.m| / (|cos_i cos_o| (wo.m + eta wi.m)^2) at m = normalize(wo + eta wi) (this includes the
// 1/eta^2 radiance scaling), G = G1(wi) G1(wo), F the dielectric Fresnel at wo.m. Sampling: a normal from the
// viewer's side, then reflection with probability F, else refraction. Both sides.
// Not supported (an error): textured alpha.
// Differences: Beckmann normals are sampled from D cos, and without sample_visible Mitsuba widens the sampled
// roughness by (1.2 - 0.2 sqrt|cos|); both change noise, not the mean.
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class RoughDielectric final : public Material {
public:
    RoughDielectric(double eta, Microfacet distribution, TexturePtr reflectance, TexturePtr transmittance)
        : eta_(eta), distribution_(distribution), reflectance_(std::move(reflectance)),
          transmittance_(std::move(transmittance)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        double density = 0;
        const double f = evaluate(wi, wo, density);
        if (pdf) *pdf = SampledSpectrum(density);
        if (!(f > 0)) return SampledSpectrum(0.0);
        const bool reflection = wi.z * wo.z > 0;
        return (reflection ? reflectance_ : transmittance_)->eval(sp.uv, w) * f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        if (wo.z == 0) return std::nullopt;
        // A facet normal in the upper hemisphere, visible from the viewer's side; the Fresnel cosine's sign then
        // tells which side of the interface the viewer is on.
        const Vec3 m = distribution_.sample(wo.z > 0 ? wo : -wo, u);
        const material::DielectricFresnel fr = material::fresnel_dielectric(dot(wo, m), eta_);
        const bool reflection = u_lobe < fr.reflectance;
        MaterialSample s;
        s.wi = reflection ? reflect(wo, m) : refract(wo, m, fr.cos_theta_t, fr.eta_ti);
        // A facet can send light to the other side than its lobe's (eval would read it as the other lobe): drop it,
        // as Mitsuba's zero shadowing term does.
        if ((s.wi.z * wo.z > 0) != reflection) return std::nullopt;
        s.f = eval(sp, s.wi, wo, w, &s.pdf);
        if (!(s.pdf[0] > 0)) return std::nullopt;
        return s;
    }

    bool has_transmission() const override { return true; }

private:
    // f(wi, wo) without the textures, and the sampling density of wi.
    double evaluate(const Vec3& wi, const Vec3& wo, double& density) const {
        density = 0;
        if (wi.z == 0 || wo.z == 0) return 0.0;
        const bool reflection = wi.z * wo.z > 0;
        const double eta = wo.z > 0 ? eta_ : 1 / eta_;  // across the interface, seen from the viewer
        Vec3 m = reflection ? wi + wo : wo + wi * eta;
        if (!(m.length() > 0)) return 0.0;
        m = normalize(m);
        if (m.z < 0) m = -m;
        const double wo_m = dot(wo, m), wi_m = dot(wi, m);
        const double G = distribution_.G(wi, wo, m);
        if (!(G > 0)) return 0.0;
        const double D = distribution_.D(m);
        const double F = material::fresnel_dielectric(wo_m, eta_).reflectance;
        // Density of the facet normal seen from the viewer, times the lobe choice, times the Jacobian to wi.
        const double pm = distribution_.pdf(wo.z > 0 ? wo : -wo, m);
        if (reflection) {
            density = pm * F / (4 * std::abs(wo_m));
            return F * D * G / (4 * std::abs(wi.z * wo.z));
        }
        const double denominator = wo_m + eta * wi_m;
        density = pm * (1 - F) * eta * eta * std::abs(wi_m) / (denominator * denominator);
        return (1 - F) * D * G * std::abs(wi_m * wo_m) / (std::abs(wi.z * wo.z) * denominator * denominator);
    }

    double eta_;
    Microfacet distribution_;
    TexturePtr reflectance_, transmittance_;
};

}  // namespace

MaterialPtr plugins::roughdielectric(Properties& props) {
    const double eta = read_relative_ior(props, "bk7", "air", true);
    const Microfacet distribution = Microfacet::read(props);
    return std::make_shared<RoughDielectric>(eta, distribution, props.get_texture("specular_reflectance", 1.0),
                                             props.get_texture("specular_transmittance", 1.0));
}

}  // namespace surfscatter::render
