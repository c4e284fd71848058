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

class SmoothDielectric final : public SmoothDielectricLobes {
public:
    using SmoothDielectricLobes::SmoothDielectricLobes;

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2) const override {
        if (wo.z == 0) return std::nullopt;
        const material::DielectricFresnel f = material::fresnel_dielectric(wo.z, eta_);
        const Vec3 refracted(-wo.x * f.eta_ti, -wo.y * f.eta_ti, f.cos_theta_t);
        return choose_lobe(sp, wo, w, u_lobe, f.reflectance, refracted, f.eta_ti * f.eta_ti);
    }
};

}  // namespace

MaterialPtr plugins::dielectric(Properties& props) { return std::make_shared<SmoothDielectric>(props); }

}  // namespace surfscatter::render
