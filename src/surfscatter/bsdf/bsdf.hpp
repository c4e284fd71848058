#pragma once
// The one BSDF interface the renderer calls (pbrt-v4's f / Sample_f / PDF, one wavelength per query).
//
// Conventions (docs/CONVENTIONS.md): local frame with z = surface normal; wi (toward the light) and wo (toward the
// viewer) both point away from the surface; wavelengths in nm; eval returns f_r in 1/sr without the cosine and
// without the specular delta. A model may have a delta lobe in the mirror direction (GHS's coherent specular part):
// its strength is delta_reflectance(), and sample() picks it with probability delta_probability().
#include <array>
#include <optional>
#include <string>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/spectrum/wavelength_sampling.hpp"

namespace surfscatter::bsdf {

// One value per wavelength of a renderer's path (spectrum::SampledWavelengths: pbrt-v4's SampledWavelengths,
// Mitsuba's spectral variants): the wavelengths themselves, f, densities.
using WavelengthValues = std::array<double, spectrum::kSpectrumSamples>;

struct BsdfSample {
    Vec3 wo;             // sampled direction, local frame, unit length, wo.z > 0
    double weight = 0;   // f * cos(theta_o) / pdf for the continuous part; delta_reflectance / pdf for the delta
    double pdf = 0;      // solid-angle density (continuous part, including the 1 - delta_probability factor),
                         // or the discrete probability of choosing the delta lobe
    bool delta = false;  // true if the specular delta lobe was chosen
};

class Bsdf {
public:
    virtual ~Bsdf() = default;

    // f_r(wi, wo) in 1/sr, no cosine, no delta. 0 if either direction is below the surface.
    virtual double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const = 0;

    // Draws wo given wi: u_lobe chooses between the delta and the continuous part, u drives the continuous sampler.
    // Returns nothing when no direction could be drawn (wi below the surface, or a sample below the horizon).
    virtual std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const = 0;

    // Solid-angle density of the continuous part of what sample() draws (times 1 - delta_probability).
    virtual double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const = 0;

    // What a spectral path tracer needs at a vertex, for all the wavelengths of its path in one call: f(wi, wo) and,
    // if `pdf` is not null, the density with which sample(wo, lambda) draws wi, pdf(wo, wi, lambda) (next-event
    // estimation and spectral MIS). The same values as eval and pdf; models override it to share the geometry and
    // the lookups that only depend on the directions (a fused eval + pdf, no virtual call per wavelength).
    virtual WavelengthValues eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                         WavelengthValues* pdf) const {
        WavelengthValues f{};
        for (std::size_t k = 0; k < f.size(); ++k) {
            f[k] = eval(wi, wo, lambda_nm[k]);
            if (pdf) (*pdf)[k] = this->pdf(wo, wi, lambda_nm[k]);
        }
        return f;
    }

    // Reflectance carried by the delta lobe toward reflect_about_normal(wi) (0 if the model has none).
    virtual double delta_reflectance(const Vec3& /*wi*/, double /*lambda_nm*/) const { return 0.0; }
    // Probability that sample() chooses the delta lobe.
    virtual double delta_probability(const Vec3& /*wi*/, double /*lambda_nm*/) const { return 0.0; }

    // Radius q = |i_xy + o_xy| about the specular direction where f jumps (the two-scale micro lobe's hole at
    // zeta_c / k), 0 if it has none: integrators put an edge there (albedo.hpp).
    virtual double jump_radius(double /*lambda_nm*/) const { return 0.0; }

    // True if f depends on the azimuths only through their difference (and is even in it): false for a surface with a
    // lay (AnisotropicGhsBsdf), whose albedo depends on the incidence azimuth.
    virtual bool isotropic() const { return true; }

    // True if the model has no continuous part (a smooth mirror).
    virtual bool is_pure_delta() const { return false; }

    virtual std::string name() const = 0;
};

}  // namespace surfscatter::bsdf
