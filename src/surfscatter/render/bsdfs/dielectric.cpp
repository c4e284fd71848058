// Mitsuba's `dielectric` BSDF: a smooth interface between two dielectrics (glass, water), two delta lobes.
//
// Supported: `int_ior` (default bk7, 1.5046), `ext_ior` (default air, 1.000277), each a number or one of Mitsuba's
// names (bsdfs/common.hpp); `specular_reflectance`, `specular_transmittance` (default 1). Exact unpolarised Fresnel;
// reflection is chosen with probability F and refraction with 1 - F, and refracted radiance is scaled by
// (eta_t / eta_i)^-2 (Mitsuba's TransportMode::Radiance). Scatters on both sides (the inside has index int_ior).
// Differences: the index does not depend on the wavelength (as Mitsuba's scalar int_ior).
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class SmoothDielectric final : public DeltaMaterial {
public:
    SmoothDielectric(double eta, TexturePtr reflectance, TexturePtr transmittance)
        : eta_(eta), reflectance_(std::move(reflectance)), transmittance_(std::move(transmittance)) {}


    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2) const override {
        if (wo.z == 0) return std::nullopt;
        const material::DielectricFresnel f = material::fresnel_dielectric(wo.z, eta_);
        MaterialSample s;
        s.delta = true;
        if (u_lobe < f.reflectance) {
            s.wi = reflect_about_normal(wo);
            s.f = reflectance_->eval(sp.uv, w) * f.reflectance;
            s.pdf = SampledSpectrum(f.reflectance);
        } else {
            s.wi = Vec3(-wo.x * f.eta_ti, -wo.y * f.eta_ti, f.cos_theta_t);
            s.f = transmittance_->eval(sp.uv, w) * ((1 - f.reflectance) * f.eta_ti * f.eta_ti);
            s.pdf = SampledSpectrum(1 - f.reflectance);
        }
        return s;
    }

    bool has_transmission() const override { return true; }

private:
    double eta_;
    TexturePtr reflectance_, transmittance_;
};

}  // namespace

MaterialPtr plugins::dielectric(Properties& props) {
    const double eta = read_relative_ior(props, "bk7", "air", true);
    return std::make_shared<SmoothDielectric>(eta, props.get_texture("specular_reflectance", 1.0),
                                              props.get_texture("specular_transmittance", 1.0));
}

}  // namespace surfscatter::render
