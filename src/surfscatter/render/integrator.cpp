#include "surfscatter/render/integrator.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include <pcg_random.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/spectrum/cie.hpp"

namespace surfscatter::render {

namespace {

constexpr int kN = spectrum::kSpectrumSamples;
constexpr int kTileSize = 16;

class Sampler {
public:
    Sampler() = default;
    Sampler(std::uint64_t seed, std::uint64_t stream) : rng_(seed, stream) {}
    double next() { return std::ldexp(static_cast<double>(rng_()), -32); }
    Vec2 next2() {
        const double a = next();
        return {a, next()};
    }

private:
    pcg32 rng_;
};

// Offset of a sample from the pixel centre, distributed as the reconstruction filter (filter importance sampling,
// as pbrt-v4), so every sample has weight 1 and stays in its own pixel.
Vec2 sample_filter(const std::string& filter, Sampler& sampler) {
    if (filter == "box") return {sampler.next() - 0.5, sampler.next() - 0.5};
    // Gaussian, stddev 0.5 pixel, truncated at 2 pixels (Mitsuba's defaults): Box-Muller with rejection.
    for (;;) {
        const double u1 = std::max(sampler.next(), 1e-300), u2 = sampler.next();
        const double r = 0.5 * std::sqrt(-2 * std::log(u1));
        const Vec2 d(r * std::cos(kTwoPi * u2), r * std::sin(kTwoPi * u2));
        if (std::abs(d.x) <= 2 && std::abs(d.y) <= 2) return d;
    }
}

double sum(const SampledSpectrum& s) {
    double total = 0;
    for (int i = 0; i < kN; ++i) total += s[i];
    return total;
}

struct PathTracer {
    const Scene& scene;
    const IntegratorSettings& settings;
    bool use_nee;
    bool use_bsdf_hits;
    std::uint64_t rays = 0;

    PathTracer(const Scene& s, const IntegratorSettings& i)
        : scene(s), settings(i), use_nee(i.strategy != "bsdf"), use_bsdf_hits(i.strategy != "emitter") {}

    // Radiance for each of the four wavelengths, already divided by the spectral MIS denominator.
    SampledSpectrum li(Ray ray, const SampledWavelengths& w, Sampler& sampler) {
        SampledSpectrum radiance(0.0), beta(1.0), ratio(1.0);
        // State of the last scattering event, for weighting emitters reached by BSDF sampling.
        bool last_delta = true;        // the camera ray counts as a delta event
        double last_pdf_hero = 0;      // hero density of the last continuous direction
        double last_ratio_sum = kN;    // sum_k r_k before the last event
        Vec3 last_point;
        for (int depth = 0;; ++depth) {
            ++rays;
            const std::optional<Hit> hit = scene.intersect(ray);
            if (!hit) {
                if (scene.has_environment()) {
                    const double p_emitter = use_nee ? scene.environment_pdf() : 0.0;
                    radiance += weighted(beta, ratio, scene.environment(w), last_delta, last_pdf_hero, last_ratio_sum, p_emitter);
                }
                break;
            }
            const SampledSpectrum le = scene.emitted(*hit, ray.direction, w);
            if (!le.is_black()) {
                const double p_emitter = use_nee && !last_delta ? scene.emitter_pdf(last_point, *hit, ray.direction) : 0.0;
                radiance += weighted(beta, ratio, le, last_delta, last_pdf_hero, last_ratio_sum, p_emitter);
            }
            if (settings.max_depth >= 0 && depth + 1 >= settings.max_depth) break;
            const Material* material = scene.material(hit->shape);
            if (!material) break;  // emitters without a BSDF absorb

            const Frame frame(hit->ns);
            const Vec3 wo = frame.to_local(-ray.direction);
            const double ratio_sum = sum(ratio);

            if (use_nee && material->has_continuous_part()) {
                const auto e = scene.sample_emitter(hit->p, sampler.next(), sampler.next2(), w);
                if (e) {
                    const Vec3 wi = frame.to_local(e->wi);
                    SampledSpectrum pdf_bsdf;
                    const bool need_pdf = !e->delta && use_bsdf_hits;
                    const SampledSpectrum f = material->eval(hit->uv, wi, wo, w, need_pdf ? &pdf_bsdf : nullptr);
                    if (!f.is_black() && dot(e->wi, hit->ng) * dot(-ray.direction, hit->ng) > 0) {
                        ++rays;
                        const Vec3 origin = Scene::offset_origin(*hit, e->wi);
                        const double t_max = std::isinf(e->distance) ? 1e30 : e->distance * (1 - 1e-4);
                        if (!scene.occluded(origin, e->wi, t_max)) {
                            double denominator = 0;
                            for (int k = 0; k < kN; ++k)
                                denominator += ratio[k] * (e->pdf + (e->delta || !use_bsdf_hits ? 0.0 : pdf_bsdf[k]));
                            denominator /= kN;
                            radiance += beta * f * e->radiance * (std::abs(wi.z) / denominator);
                        }
                    }
                }
            }

            const auto s = material->sample(hit->uv, wo, w, sampler.next(), sampler.next2());
            if (!s) break;
            const double pdf_hero = s->pdf[0];
            if (!(pdf_hero > 0)) break;
            beta *= s->f * ((s->delta ? 1.0 : std::abs(s->wi.z)) / pdf_hero);
            for (int k = 0; k < kN; ++k) ratio[k] *= s->pdf[k] / pdf_hero;
            last_delta = s->delta;
            last_pdf_hero = pdf_hero;
            last_ratio_sum = ratio_sum;
            last_point = hit->p;
            if (beta.is_black()) break;

            if (depth + 1 >= settings.rr_depth) {
                const double estimate = (beta * (kN / sum(ratio))).max_value();
                if (estimate < 1) {
                    const double q = std::max(0.05, 1 - estimate);
                    if (sampler.next() < q) break;
                    beta *= 1 / (1 - q);
                }
            }
            const Vec3 wi_world = frame.to_world(s->wi);
            ray = Ray{Scene::offset_origin(*hit, wi_world), wi_world, 0.0, 1e30};
        }
        return radiance;
    }

    // beta_j Le_j / ((1/4) (sum_k r_k + (p_emitter / p_hero) sum_k r_k,before)): see integrator.hpp.
    SampledSpectrum weighted(const SampledSpectrum& beta, const SampledSpectrum& ratio, const SampledSpectrum& le,
                             bool last_delta, double last_pdf_hero, double last_ratio_sum, double p_emitter) const {
        if (!last_delta && !use_bsdf_hits) return SampledSpectrum(0.0);
        double denominator = sum(ratio);
        if (!last_delta && p_emitter > 0) denominator += p_emitter / last_pdf_hero * last_ratio_sum;
        return beta * le * (kN / denominator);
    }
};

}  // namespace

Film render(const Scene& scene, const RenderOptions& options, RenderStats* stats) {
    scene.film.check_crop();
    const Camera camera(scene.camera, scene.film.width, scene.film.height);
    const int width = scene.film.output_width(), height = scene.film.output_height();
    const int offset_x = scene.film.crop_offset_x, offset_y = scene.film.crop_offset_y;
    const int spp = options.spp > 0 ? options.spp : scene.sampler.sample_count;
    if (spp <= 0) fail("sample count must be positive, got {}", spp);
    const std::uint64_t seed = options.seed.value_or(scene.sampler.seed);
    const IntegratorSettings& integrator = scene.integrator;
    if (integrator.strategy != "mis" && integrator.strategy != "bsdf" && integrator.strategy != "emitter")
        fail("integrator strategy must be mis, bsdf or emitter, got '{}'", integrator.strategy);

    const spectrum::CieTable& cie = spectrum::cie1931();
    // Y of a constant unit spectrum over the sampled range, so that it maps to Y = 1.
    double y_integral = 0;
    for (double lambda = spectrum::kSampledLambdaMin; lambda <= spectrum::kSampledLambdaMax; lambda += 1.0)
        y_integral += cie.xyz_bar(lambda).y;

    Film film(width, height);
    std::vector<Sampler> samplers(static_cast<std::size_t>(width) * height);
    // Streams are indexed by full-film pixel, so a crop reproduces the same pixels of the full render.
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            samplers[static_cast<std::size_t>(y) * width + x] =
                Sampler(seed, static_cast<std::uint64_t>(y + offset_y) * static_cast<std::uint64_t>(scene.film.width) +
                                  static_cast<std::uint64_t>(x + offset_x));

    const int tiles_x = (width + kTileSize - 1) / kTileSize, tiles_y = (height + kTileSize - 1) / kTileSize;
    const int per_pass = std::max(1, spp / 16);
    Progress progress("render", static_cast<std::uint64_t>(spp) * tiles_x * tiles_y, options.progress);
    std::atomic<std::uint64_t> rays{0};
    const auto start = std::chrono::steady_clock::now();
    int done = 0;
    bool interrupted = false;

    tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
    while (done < spp) {
        if (interrupt_requested()) {
            interrupted = true;
            break;
        }
        const int count = std::min(per_pass, spp - done);
        arena.execute([&] {
            tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& range) {
                PathTracer tracer(scene, integrator);
                for (int tile = range.begin(); tile != range.end(); ++tile) {
                    const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
                    for (int y = y0; y < std::min(y0 + kTileSize, height); ++y)
                        for (int x = x0; x < std::min(x0 + kTileSize, width); ++x) {
                            Sampler& sampler = samplers[static_cast<std::size_t>(y) * width + x];
                            for (int s = 0; s < count; ++s) {
                                const SampledWavelengths w = SampledWavelengths::sample_visible(sampler.next());
                                const Vec2 offset = sample_filter(scene.film.filter, sampler);
                                const Ray ray = camera.generate_ray(x + offset_x + 0.5 + offset.x,
                                                                                   y + offset_y + 0.5 + offset.y);
                                const SampledSpectrum l = tracer.li(ray, w, sampler);
                                Vec3 xyz;
                                for (int k = 0; k < kN; ++k) {
                                    const double lambda = w.lambda[static_cast<std::size_t>(k)];
                                    const double value = l[k] / (w.pdf[static_cast<std::size_t>(k)] * kN * y_integral);
                                    if (!std::isfinite(value)) continue;  // a degenerate path; never seen in tests
                                    xyz += cie.xyz_bar(lambda) * value;
                                }
                                film.add(x, y, xyz);
                            }
                        }
                    progress.advance(static_cast<std::uint64_t>(count));
                }
                rays += tracer.rays;
            });
        });
        done += count;
    }
    progress.finish();
    if (stats) {
        stats->samples_per_pixel = done;
        stats->interrupted = interrupted;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = rays.load();
    }
    return film;
}

}  // namespace surfscatter::render
