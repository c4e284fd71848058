#pragma once
// The render loop: pixels in 16x16 tiles over oneTBB workers, samples placed by the reconstruction filter, radiance
// from the scene's integrator (integrators/path.cpp, integrators/direct.cpp; estimator.hpp explains the spectral
// and strategy MIS they share), accumulated as XYZ on the film.
#include <cstdint>
#include <optional>
#include <string>

#include "surfscatter/render/film.hpp"

namespace surfscatter {
class Progress;
}

namespace surfscatter::render {

struct RenderOptions {
    int spp = 0;                          // 0: the scene's sampler sample_count
    int threads = 0;                      // 0: all hardware threads
    std::optional<std::uint64_t> seed;    // default: the scene's sampler seed
    bool progress = true;                 // percentage and ETA on stderr
    // Render only the 16x16 tiles t (row-major over the output image) with t % parts == part; the film keeps its
    // full size and the other pixels stay empty. No pixel depends on the split, so the films of parts
    // 0 .. parts-1 summed (Film::accumulate) are the whole render, bit for bit.
    int part = 0;
    int parts = 1;
    // When set, the render advances this bar (in pixel samples: the whole render, all parts, is output width x
    // height x spp of them) instead of drawing one of its own.
    Progress* shared_progress = nullptr;
};

// Samples per pixel the options ask of the scene (its sampler's sample_count unless options.spp is set).
int samples_per_pixel(const Scene& scene, const RenderOptions& options);

struct RenderStats {
    int samples_per_pixel = 0;      // taken at every pixel (fewer than asked if interrupted)
    int max_samples_per_pixel = 0;  // taken at the pixels that got most (more than the above if interrupted mid-pass)
    bool interrupted = false;
    double seconds = 0;
    std::uint64_t rays = 0;     // intersection and shadow rays traced
    // Spectral samples whose radiance was NaN or infinite (a degenerate path), left out of the film: the callers
    // report them, since the pixels they fell in are biased.
    std::uint64_t nonfinite_samples = 0;
};

// One line telling how many spectral samples were left out as non-finite, or empty if none.
std::string nonfinite_note(const RenderStats& stats);

// Renders the scene. Deterministic: every pixel owns a PCG32 stream seeded by (seed, pixel index), and samples are
// taken in passes, so the image is identical for any thread count and any split into parts. On Ctrl-C or SIGTERM
// (core/progress.hpp) every thread stops before its next sample and the film holds what was taken; its per-pixel
// counts make every pixel the mean of its own samples. Throws Error for bad film settings or thread counts
// (scene.hpp, core/resources.hpp).
Film render(const Scene& scene, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace surfscatter::render
