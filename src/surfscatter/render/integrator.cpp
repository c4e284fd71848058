#include "surfscatter/render/integrator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/render/estimator.hpp"
#include "surfscatter/spectrum/cie.hpp"

namespace surfscatter::render {

namespace {

constexpr int kN = spectrum::kSpectrumSamples;

std::unique_ptr<RadianceEstimator> make_estimator(const Scene& scene) {
    if (scene.integrator.type == "path") return make_path_estimator(scene);
    if (scene.integrator.type == "direct") return make_direct_estimator(scene);
    fail("unknown integrator '{}' (path, direct)", scene.integrator.type);
}

}  // namespace

int samples_per_pixel(const Scene& scene, const RenderOptions& options) {
    const int spp = options.spp > 0 ? options.spp : scene.sampler.sample_count;
    if (spp <= 0) fail("sample count must be positive, got {}", spp);
    return spp;
}

Film render(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
    scene.film.check();
    require_thread_count(options.threads, "threads");
    const Camera camera(scene.camera, scene.film.width, scene.film.height);
    const FilterPtr filter = scene.film.filter ? scene.film.filter : make_gaussian_filter();
    const int width = scene.film.output_width(), height = scene.film.output_height();
    const int offset_x = scene.film.crop_offset_x, offset_y = scene.film.crop_offset_y;
    const int spp = samples_per_pixel(scene, options);
    if (options.parts < 1 || options.part < 0 || options.part >= options.parts)
        fail("render part {} of {} does not exist", options.part, options.parts);
    const std::uint64_t seed = options.seed.value_or(scene.sampler.seed);
    const IntegratorSettings& integrator = scene.integrator;
    if (integrator.strategy != "mis" && integrator.strategy != "bsdf" && integrator.strategy != "emitter")
        fail("integrator strategy must be mis, bsdf or emitter, got '{}'", integrator.strategy);
    make_estimator(scene);  // reports a bad integrator before any work

    const spectrum::CieTable& cie = spectrum::cie1931();
    // Y of a constant unit spectrum over the sampled range, so that it maps to Y = 1.
    double y_integral = 0;
    for (double lambda = spectrum::kSampledLambdaMin; lambda <= spectrum::kSampledLambdaMax; lambda += 1.0)
        y_integral += cie.xyz_bar(lambda).y;

    Film film(width, height);
    TiledPixels<Sampler> samplers(width, height);
    // Streams are indexed by full-film pixel, so a crop reproduces the same pixels of the full render.
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            samplers(x, y) = Sampler(seed, static_cast<std::uint64_t>(y + offset_y) * static_cast<std::uint64_t>(scene.film.width) +
                                               static_cast<std::uint64_t>(x + offset_x));
    // Without sample_border, sample positions stay inside the crop window (film pixels [offset, offset + size)).
    const double unbounded = 1e30;
    const double window_x0 = scene.film.sample_border ? -unbounded : offset_x;
    const double window_y0 = scene.film.sample_border ? -unbounded : offset_y;
    const double window_x1 = scene.film.sample_border ? unbounded : offset_x + width;
    const double window_y1 = scene.film.sample_border ? unbounded : offset_y + height;

    const int tiles_x = samplers.order().tiles_x(), tiles_y = samplers.order().tiles_y();
    const auto tile_pixels = [&](int tile) {
        const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
        return static_cast<std::uint64_t>(std::min(kTileSize, width - x0)) * std::min(kTileSize, height - y0);
    };
    std::vector<int> tiles;
    std::uint64_t part_pixels = 0;
    for (int tile = options.part; tile < tiles_x * tiles_y; tile += options.parts) {
        tiles.push_back(tile);
        part_pixels += tile_pixels(tile);
    }
    // Passes of 1, 2, 4, ... samples up to spp/16: an early Ctrl-C still leaves every pixel with samples.
    const int max_pass = std::max(1, spp / 16);
    int per_pass = 1;
    Progress own_progress("render", part_pixels * static_cast<std::uint64_t>(spp),
                          options.progress && !options.shared_progress);
    Progress& progress = options.shared_progress ? *options.shared_progress : own_progress;
    std::atomic<std::uint64_t> rays{0}, nonfinite{0};
    const auto start = std::chrono::steady_clock::now();
    int done = 0;

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    // Ctrl-C is polled before every sample, so a render stops within one sample per thread at any spp; the film
    // keeps per-pixel sample counts, so the pixels of the unfinished pass stay correct means of what they have.
    while (done < spp && !interrupt_requested()) {
        const int count = std::min(per_pass, spp - done);
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size()), [&](const tbb::blocked_range<std::size_t>& range) {
                const std::unique_ptr<RadianceEstimator> estimator = make_estimator(scene);
                std::uint64_t left_out = 0;
                for (std::size_t i = range.begin(); i != range.end(); ++i) {
                    const int tile = tiles[i];
                    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                    for (int y = y0; y < std::min(y0 + kTileSize, height); ++y)
                        for (int x = x0; x < std::min(x0 + kTileSize, width); ++x) {
                            Sampler& sampler = samplers(x, y);
                            const double cx = x + offset_x + 0.5, cy = y + offset_y + 0.5;
                            for (int s = 0; s < count && !interrupt_requested(); ++s) {
                                const SampledWavelengths w = SampledWavelengths::sample_visible(sampler.next());
                                const ReconstructionFilter::Sample fs = filter->sample(
                                    sampler.next2(), {window_x0 - cx, window_y0 - cy}, {window_x1 - cx, window_y1 - cy});
                                const Vec2 lens = camera.has_aperture() ? sampler.next2() : Vec2(0.5, 0.5);
                                const Ray ray = camera.generate_ray(cx + fs.offset.x, cy + fs.offset.y, lens);
                                bool covered = false;
                                const SampledSpectrum l = estimator->li(ray, w, sampler, covered);
                                Vec3 xyz;
                                for (int k = 0; k < kN; ++k) {
                                    const double lambda = w.lambda[static_cast<std::size_t>(k)];
                                    const double value = l[k] / (w.pdf[static_cast<std::size_t>(k)] * kN * y_integral);
                                    if (!std::isfinite(value)) {  // a degenerate path: counted and reported
                                        ++left_out;
                                        continue;
                                    }
                                    xyz += cie.xyz_bar(lambda) * value;
                                }
                                film.add(x, y, xyz, fs.weight, covered);
                            }
                        }
                    progress.advance(tile_pixels(tile) * static_cast<std::uint64_t>(count));
                }
                rays += estimator->rays;
                nonfinite += left_out;
            });
        });
        done += count;
        per_pass = std::min(2 * per_pass, max_pass);
    }
    own_progress.finish();
    if (stats) {
        // Over this part's pixels only: the other parts' pixels are empty by design.
        std::uint32_t fewest = UINT32_MAX, most = 0;
        for (const int tile : tiles) {
            const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
            for (int y = y0; y < std::min(y0 + kTileSize, height); ++y)
                for (int x = x0; x < std::min(x0 + kTileSize, width); ++x) {
                    fewest = std::min(fewest, film.samples(x, y));
                    most = std::max(most, film.samples(x, y));
                }
        }
        if (tiles.empty()) fewest = static_cast<std::uint32_t>(spp);  // a part with no tiles (more parts than tiles)
        stats->samples_per_pixel = static_cast<int>(fewest);
        stats->max_samples_per_pixel = static_cast<int>(most);
        stats->interrupted = static_cast<int>(fewest) < spp;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = rays.load();
        stats->nonfinite_samples = nonfinite.load();
    }
    return film;
}

std::string nonfinite_note(const RenderStats& stats) {
    if (stats.nonfinite_samples == 0) return {};
    return fmt::format("{} spectral samples had a NaN or infinite radiance (degenerate paths) and were left out: the "
                       "pixels they fell in are biased low",
                       stats.nonfinite_samples);
}

}  // namespace surfscatter::render
