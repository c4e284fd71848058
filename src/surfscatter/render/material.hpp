#pragma once
// What the path tracer sees at a surface point: a BSDF evaluated for the four sampled wavelengths at once.
//
// Directions are in the local shading frame (z = normal) and point away from the surface. `wo` is the direction
// toward the viewer (the previous path vertex) and `wi` the direction toward the light; f(wi, wo) is the BSDF of
// bsdf.hpp (1/sr, no cosine). sample() draws wi given wo with the hero wavelength w.lambda[0]; the returned pdf holds
// the density every wavelength's own sampler would have had for that direction (spectral MIS), so that models whose
// lobes change with wavelength (GHS) stay unbiased and low-variance. Surfaces are one-sided as in Mitsuba: a BSDF is
// zero when wo is below the surface unless it is wrapped in `twosided`.
#include <memory>
#include <optional>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/render/texture.hpp"

namespace surfscatter::render {

struct MaterialSample {
    Vec3 wi;               // toward the light, local frame
    SampledSpectrum f;     // continuous: f(wi, wo); delta: the delta lobe's reflectance
    SampledSpectrum pdf;   // per wavelength: solid-angle density (continuous) or lobe probability (delta)
    bool delta = false;
};

class Material {
public:
    virtual ~Material() = default;
    // f(wi, wo) per wavelength; `pdf` (if not null) receives each wavelength's sampling density of wi given wo.
    // Light from point emitters needs no density, and for the scattering models the density costs as much as f.
    virtual SampledSpectrum eval(Vec2 uv, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                                 SampledSpectrum* pdf) const = 0;
    virtual std::optional<MaterialSample> sample(Vec2 uv, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                                 Vec2 u) const = 0;
    // False for pure mirrors: next-event estimation is skipped.
    virtual bool has_continuous_part() const { return true; }
};
using MaterialPtr = std::shared_ptr<const Material>;

// Lambertian, one-sided: f = reflectance / pi, cosine-weighted sampling.
MaterialPtr make_diffuse(TexturePtr reflectance);

// Smooth conductor: a pure delta lobe of reflectance specular_reflectance * Fresnel(cos, lambda). The index comes from
// `conductor` (a tabulated copy over 360-830 nm is made once) or from eta/k spectra when `conductor` is empty.
MaterialPtr make_smooth_conductor(const std::optional<material::Conductor>& conductor, SpectrumPtr eta, SpectrumPtr k,
                                  TexturePtr specular_reflectance);

// A surfscatter scattering model (bsdf/factory.hpp) used per wavelength.
MaterialPtr make_model_material(std::shared_ptr<const bsdf::Bsdf> model);

// Mitsuba's twosided: the nested BSDF on both faces (directions mirrored through the surface for the back face).
MaterialPtr make_twosided(MaterialPtr nested);

}  // namespace surfscatter::render
