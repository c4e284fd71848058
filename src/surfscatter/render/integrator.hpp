#pragma once
// The render loop: pixels in 16x16 tiles over oneTBB workers, samples placed by the reconstruction filter, radiance
// from the scene's integrator (integrators/path.cpp, integrators/direct.cpp; estimator.hpp explains the spectral
// and strategy MIS they share), accumulated as XYZ on the film.
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
    int samples_per_pixel = 0;      // taken at every pixel (fewer than asked if interrupted)
    int max_samples_per_pixel = 0;  // taken at the pixels that got most (more than the above if interrupted mid-pass)
    bool interrupted = false;
    double seconds = 0;
    std::uint64_t rays = 0;     // intersection and shadow rays traced
};

// Renders the scene. Deterministic: every pixel owns a PCG32 stream seeded by (seed, pixel index), and samples are
// taken in passes, so the image is identical for any thread count. On Ctrl-C or SIGTERM (core/progress.hpp) every
// thread stops before its next sample and the film holds what was taken; its per-pixel counts make every pixel the
// mean of its own samples. Throws Error for bad film settings or thread counts (scene.hpp, core/resources.hpp).
Film render(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace surfscatter::render
