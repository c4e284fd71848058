// Mitsuba's `conductor` BSDF: a smooth metal, a delta lobe of reflectance specular_reflectance x Fresnel.
//
// Supported: `material` (Mitsuba's names of built-in metals: Ag, Al, Au, Be, Cr, Cu, W, and surfscatter's Ni, Pd,
// Pt, Ti, all Rakic et al. 1998 Lorentz-Drude fits; `none` (default) = a perfect mirror; or a refractiveindex.info
// .yml / wavelength_nm,n,k .csv file), or `eta` and `k` spectra (defaults 0 and 1: a perfect mirror, as Mitsuba),
// e.g. from .spd files; `specular_reflectance` (default 1). Exact unpolarised Fresnel per wavelength (1 nm table).
// One-sided (use twosided).
// Differences: Mitsuba's other presets (a-C, Hg, Ir, ..., and the *_palik tables) are errors: surfscatter ships the
// Rakic data, not Palik's; eta and k are spectra, not textures.
#include "surfscatter/render/bsdfs/common.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class SmoothConductor final : public DeltaMaterial {
public:
    SmoothConductor(ConductorIor ior, TexturePtr specular) : ior_(std::move(ior)), specular_(std::move(specular)) {}


    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w, double,
                                         Vec2) const override {
        if (wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = reflect_about_normal(wo);
        s.delta = true;
        s.pdf = SampledSpectrum(1.0);
        s.f = specular_->eval(sp.uv, w);
        s.f *= ior_.reflectance(wo.z, w);
        return s;
    }


private:
    ConductorIor ior_;
    TexturePtr specular_;
};

}  // namespace

MaterialPtr plugins::conductor(Properties& props) {
    ConductorIor ior = read_conductor_ior(props);
    return std::make_shared<SmoothConductor>(std::move(ior), props.get_texture("specular_reflectance", 1.0));
}

}  // namespace surfscatter::render
