#pragma once
// What the path tracer sees at a surface point: a BSDF evaluated for the four sampled wavelengths at once.
//
// Directions are in the local shading frame (z = shading normal, x along dp/du as Mitsuba's sh_frame) and point
// away from the surface. `wo` is the direction toward the viewer (the previous path vertex) and `wi` the direction
// toward the light; f(wi, wo) is the BSDF of bsdf.hpp (1/sr, no cosine). wi.z < 0 < wo.z (or the reverse) is
// transmission; for radiance the transmitted f already carries the 1/eta^2 of the solid-angle compression, as in
// Mitsuba's TransportMode::Radiance. sample() draws wi given wo with the hero wavelength w.lambda[0]; the returned
// pdf holds the density every wavelength's own sampler would have had for that direction (spectral MIS), so that
// models whose lobes change with wavelength (GHS) stay unbiased and low-variance. Surfaces are one-sided as in
// Mitsuba: a reflecting BSDF is zero when wo is below the surface unless it is wrapped in `twosided`; dielectrics
// scatter on both sides.
#include <memory>
#include <optional>
#include <string>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/render/texture.hpp"

namespace surfscatter::render {

// Where a material is evaluated: texture coordinates and the surface's parametric derivatives expressed in the local
// shading frame (bumpmap and normalmap perturb that frame; the others only read uv).
struct ShadingPoint {
    Vec2 uv;
    Vec3 dpdu{1, 0, 0};
    Vec3 dpdv{0, 1, 0};
};

struct MaterialSample {
    Vec3 wi;               // toward the light, local frame
    SampledSpectrum f;     // continuous: f(wi, wo); delta: the delta lobe's reflectance (or transmittance)
    SampledSpectrum pdf;   // per wavelength: solid-angle density (continuous) or lobe probability (delta)
    bool delta = false;
};

class Material {
public:
    virtual ~Material() = default;
    // f(wi, wo) per wavelength; `pdf` (if not null) receives each wavelength's sampling density of wi given wo.
    // Light from point emitters needs no density, and for the scattering models the density costs as much as f.
    virtual SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                                 SampledSpectrum* pdf) const = 0;
    virtual std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                                 double u_lobe, Vec2 u) const = 0;
    // False for pure delta materials (mirrors, smooth glass): next-event estimation is skipped.
    virtual bool has_continuous_part() const { return true; }
    // True if light can pass to the other side of the surface (next-event estimation then looks on both sides).
    virtual bool has_transmission() const { return false; }
};
using MaterialPtr = std::shared_ptr<const Material>;

// Materials made of delta lobes only (smooth conductors and dielectrics): f is zero for every pair of directions.
class DeltaMaterial : public Material {
public:
    SampledSpectrum eval(const ShadingPoint&, const Vec3&, const Vec3&, const SampledWavelengths&,
                         SampledSpectrum* pdf) const final {
        if (pdf) *pdf = SampledSpectrum(0.0);
        return SampledSpectrum(0.0);
    }
    bool has_continuous_part() const final { return false; }
};

// Lambertian reflectance used where a scene gives a shape no BSDF (Mitsuba's default diffuse 0.5).
MaterialPtr make_diffuse(TexturePtr reflectance);

// A surfscatter scattering model (bsdf/factory.hpp) used per wavelength.
MaterialPtr make_model_material(std::shared_ptr<const bsdf::Bsdf> model);

// Sampling warps shared by the materials (Mitsuba's warp:: names).
Vec3 square_to_cosine_hemisphere(Vec2 u);        // density cos(theta) / pi
Vec2 square_to_uniform_disk_concentric(Vec2 u);  // unit disk, density 1 / pi

}  // namespace surfscatter::render
