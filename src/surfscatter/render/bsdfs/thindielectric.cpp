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

class ThinDielectric final : public SmoothDielectricLobes {
public:
    using SmoothDielectricLobes::SmoothDielectricLobes;

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2) const override {
        if (wo.z == 0) return std::nullopt;
        const double f = material::fresnel_dielectric(std::abs(wo.z), eta_).reflectance;
        const double r = f < 1 ? f + (1 - f) * (1 - f) * f / (1 - f * f) : 1.0;
        return choose_lobe(sp, wo, w, u_lobe, r, -wo, 1.0);
    }
};

}  // namespace

MaterialPtr plugins::thindielectric(Properties& props) { return std::make_shared<ThinDielectric>(props); }

}  // namespace surfscatter::render
