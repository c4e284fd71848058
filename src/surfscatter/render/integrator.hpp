#pragma once
// Spectral path tracer (hero wavelengths, next-event estimation, spectral and strategy MIS, Russian roulette).
//
// Estimator. A path carries four wavelengths (spectrum/wavelength_sampling.hpp); directions are sampled for the hero.
// For wavelength j the contribution of a path x is f_j(x) / ((1/4) sum_k p_k(x)), the balance heuristic over the
// four ways (one per hero) the same path could have been drawn (Wilkie et al. 2014), where p_k is the density with
// wavelength k as hero. At a vertex where a light is reached, p_k includes both strategies: p_k = prefix_k *
// (p_emitter + p_bsdf,k), so next-event estimation and BSDF sampling are combined by the balance heuristic as well.
// The tracer keeps beta_j = f_j / p_hero and the ratios r_k = prefix_k / prefix_hero, which keeps the arithmetic in
// range. Delta lobes and point lights take part with their discrete probabilities (no strategy MIS for them).
#include <cstdint>
#include <optional>

#include "surfscatter/render/film.hpp"

namespace surfscatter::render {

struct RenderOptions {
    int spp = 0;                          // 0: the scene's sampler sample_count
    int threads = 0;                      // 0: all hardware threads
    std::optional<std::uint64_t> seed;    // default: the scene's sampler seed
    bool progress = true;                 // percentage and ETA on stderr
};

struct RenderStats {
    int samples_per_pixel = 0;  // completed for every pixel (fewer than asked if interrupted)
    bool interrupted = false;
    double seconds = 0;
    std::uint64_t rays = 0;     // intersection and shadow rays traced
};

// Renders the scene. Deterministic: every pixel owns a PCG32 stream seeded by (seed, pixel index), and samples are
// taken in passes, so the image is identical for any thread count. On Ctrl-C (core/progress.hpp) the current pass
// ends and the film holds the passes completed so far.
Film render(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace surfscatter::render
