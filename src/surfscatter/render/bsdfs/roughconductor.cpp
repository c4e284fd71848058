// Mitsuba's `roughconductor` BSDF: a microfacet metal (Walter et al. 2007) with exact conductor Fresnel.
//
// Supported: `distribution` (beckmann (Mitsuba's default) | ggx), `alpha` (default 0.1), or `alpha_u` (along the
// shading frame's s = dp/du) and `alpha_v` (along t) for an anisotropic lobe,
// `sample_visible` (default true; honoured for ggx), `material` / `eta` + `k` (as conductor.cpp),
// `specular_reflectance` (default 1). f = F(wo.m) D(m) G1(wi) G1(wo) / (4 cos_i cos_o), m the half vector.
// One-sided. For roughness from measured surface statistics use surfscatter's ggx_stats (scattering_models.cpp).
// Not supported (an error): textured alpha.
// Differences: Beckmann normals are sampled from D cos (Mitsuba samples its visible normals); noise, not mean.
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class RoughConductor final : public Material {
public:
    RoughConductor(Microfacet distribution, ConductorIor ior, TexturePtr specular)
        : distribution_(distribution), ior_(std::move(ior)), specular_(std::move(specular)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (pdf) *pdf = SampledSpectrum(0.0);
        if (wi.z <= 0 || wo.z <= 0) return SampledSpectrum(0.0);
        const Vec3 m = normalize(wi + wo);
        const double common = distribution_.D(m) * distribution_.G(wi, wo, m) / (4 * wi.z * wo.z);
        if (pdf) *pdf = SampledSpectrum(density(wo, m));
        if (!(common > 0)) return SampledSpectrum(0.0);
        return specular_->eval(sp.uv, w) * ior_.reflectance(dot(wo, m), w) * common;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double,
                                         Vec2 u) const override {
        if (wo.z <= 0) return std::nullopt;
        const Vec3 m = distribution_.sample(wo, u);
        MaterialSample s;
        s.wi = reflect(wo, m);
        if (s.wi.z <= 0) return std::nullopt;
        s.f = eval(sp, s.wi, wo, w, &s.pdf);
        if (!(s.pdf[0] > 0)) return std::nullopt;
        return s;
    }

private:
    // Solid-angle density of wi = reflect(wo, m).
    double density(const Vec3& wo, const Vec3& m) const {
        const double wo_m = dot(wo, m);
        return wo_m > 0 ? distribution_.pdf(wo, m) / (4 * wo_m) : 0.0;
    }

    Microfacet distribution_;
    ConductorIor ior_;
    TexturePtr specular_;
};

}  // namespace

MaterialPtr plugins::roughconductor(Properties& props) {
    const Microfacet distribution = Microfacet::read(props);
    ConductorIor ior = read_conductor_ior(props);
    return std::make_shared<RoughConductor>(distribution, std::move(ior), props.get_texture("specular_reflectance", 1.0));
}

}  // namespace surfscatter::render
