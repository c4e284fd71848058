#pragma once
// The per-thread radiance estimators behind the integrator plugins (integrators/path.cpp, integrators/direct.cpp).
//
// Spectral MIS (shared by both). A path carries four wavelengths (spectrum/wavelength_sampling.hpp); directions are
// sampled for the hero. For wavelength j the contribution of a path x is f_j(x) / ((1/4) sum_k p_k(x)), the balance
// heuristic over the four ways (one per hero) the same path could have been drawn (Wilkie et al. 2014), where p_k
// is the density with wavelength k as hero. Where an emitter is reached, p_k includes every strategy that could have
// produced the last direction (next-event estimation and BSDF sampling, each times its number of samples), so the
// strategy MIS and the spectral MIS are one balance heuristic. Delta lobes and delta emitters take part with their
// discrete probabilities (no strategy MIS for them).
#include <cstdint>
#include <memory>

#include "surfscatter/render/sampler.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

class RadianceEstimator {
public:
    virtual ~RadianceEstimator() = default;
    // Radiance for each of the four wavelengths along a camera ray, already divided by the spectral MIS denominator.
    // `alpha` is set to whether the pixel is covered (Mitsuba: the ray met a surface, or an environment emitter is
    // visible).
    virtual SampledSpectrum li(const Ray& ray, const SampledWavelengths& w, Sampler& sampler, bool& alpha) = 0;
    std::uint64_t rays = 0;  // intersection and shadow rays traced
};

std::unique_ptr<RadianceEstimator> make_path_estimator(const Scene& scene);
std::unique_ptr<RadianceEstimator> make_direct_estimator(const Scene& scene);

// Next-event estimation shared by the estimators: an emitter sample seen through the material at `hit`, with the
// material's per-wavelength densities for the sampled direction (zero for delta emitters). Returns nothing when the
// emitter is occluded or the BSDF is zero. `rays` counts the shadow ray.
struct LightSample {
    SampledSpectrum f_cos_le;  // f(wi, wo) |cos| Le (Le includes 1/d^2 for point-like emitters)
    SampledSpectrum bsdf_pdf;  // per wavelength, 0 for delta emitters
    double emitter_pdf = 0;    // solid angle (area, environment) or choice probability (delta)
    bool delta = false;
};
std::optional<LightSample> sample_light(const Scene& scene, const Hit& hit, const Frame& frame, const Material& material,
                                        const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                        Sampler& sampler, bool need_bsdf_pdf, std::uint64_t& rays);

// The shading point of a hit (uv and the parametric derivatives in the shading frame).
ShadingPoint shading_point(const Hit& hit, const Frame& frame);

}  // namespace surfscatter::render
