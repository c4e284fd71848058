// Mitsuba's `thindielectric` BSDF: a thin slab (a window pane) with parallel smooth faces: light is reflected or
// passes straight through, the internal reflections summed in closed form.
//
// Supported: `int_ior` (default bk7), `ext_ior` (default air), `specular_reflectance`, `specular_transmittance`
// (default 1). With F the Fresnel reflectance of one face at the incidence angle, the slab reflects
// R = F + (1 - F)^2 F / (1 - F^2) and transmits 1 - R along -wo (no refraction offset, as Mitsuba). Both sides.
// Differences: none.
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class ThinDielectric final : public DeltaMaterial {
public:
    ThinDielectric(double eta, TexturePtr reflectance, TexturePtr transmittance)
        : eta_(eta), reflectance_(std::move(reflectance)), transmittance_(std::move(transmittance)) {}


    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2) const override {
        if (wo.z == 0) return std::nullopt;
        const double f = material::fresnel_dielectric(std::abs(wo.z), eta_).reflectance;
        const double r = f < 1 ? f + (1 - f) * (1 - f) * f / (1 - f * f) : 1.0;
        MaterialSample s;
        s.delta = true;
        if (u_lobe < r) {
            s.wi = reflect_about_normal(wo);
            s.f = reflectance_->eval(sp.uv, w) * r;
            s.pdf = SampledSpectrum(r);
        } else {
            s.wi = -wo;
            s.f = transmittance_->eval(sp.uv, w) * (1 - r);
            s.pdf = SampledSpectrum(1 - r);
        }
        return s;
    }

    bool has_transmission() const override { return true; }

private:
    double eta_;
    TexturePtr reflectance_, transmittance_;
};

}  // namespace

MaterialPtr plugins::thindielectric(Properties& props) {
    const double eta = read_relative_ior(props, "bk7", "air", true);
    return std::make_shared<ThinDielectric>(eta, props.get_texture("specular_reflectance", 1.0),
                                            props.get_texture("specular_transmittance", 1.0));
}

}  // namespace surfscatter::render
