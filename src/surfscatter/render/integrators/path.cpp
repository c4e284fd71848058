// Mitsuba's `path` integrator: unidirectional path tracing with next-event estimation and multiple importance
// sampling (estimator.hpp: the spectral and strategy MIS, one balance heuristic).
//
// Supported: `max_depth` (default -1 = unbounded; 1 = emitters seen directly, 2 = direct lighting, Mitsuba's
// meaning), `rr_depth` (default 5: first depth at which Russian roulette may end a path; survival = the
// MIS-weighted throughput, at most 0.95), `hide_emitters` (default false: emitters seen directly by the camera are
// black, and so is the alpha of pixels that see only the environment). surfscatter extension `strategy` = `mis`
// (default) | `bsdf` | `emitter` selects the strategies that reach emitters, to test the estimator.
// Differences from Mitsuba: the balance heuristic (Mitsuba: power heuristic) and hero-wavelength spectral MIS; no
// participating media.
#include <algorithm>
#include <cmath>

#include "surfscatter/render/estimator.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

constexpr int kN = spectrum::kSpectrumSamples;

double sum(const SampledSpectrum& s) {
    double total = 0;
    for (int i = 0; i < kN; ++i) total += s[i];
    return total;
}

class PathEstimator final : public RadianceEstimator {
public:
    explicit PathEstimator(const Scene& scene)
        : scene_(scene), settings_(scene.integrator), use_nee_(settings_.strategy != "bsdf"),
          use_bsdf_hits_(settings_.strategy != "emitter") {}

    SampledSpectrum li(const Ray& camera_ray, const SampledWavelengths& w, Sampler& sampler, bool& alpha) override {
        Ray ray = camera_ray;
        SampledSpectrum radiance(0.0), beta(1.0), ratio(1.0);
        // State of the last scattering event, for weighting emitters reached by BSDF sampling.
        bool last_delta = true;        // the camera ray counts as a delta event
        double last_pdf_hero = 0;      // hero density of the last continuous direction
        double last_ratio_sum = kN;    // sum_k r_k before the last event
        Vec3 last_point;
        alpha = !settings_.hide_emitters && scene_.has_environment();
        for (int depth = 0;; ++depth) {
            ++rays;
            const std::optional<Hit> hit = scene_.intersect(ray);
            const bool visible = depth > 0 || !settings_.hide_emitters;
            if (!hit) {
                if (scene_.has_environment() && visible) {
                    const double p_emitter = use_nee_ ? scene_.environment_pdf(ray.direction) : 0.0;
                    radiance += weighted(beta, ratio, scene_.environment(ray.direction, w), last_delta, last_pdf_hero,
                                         last_ratio_sum, p_emitter);
                }
                break;
            }
            if (depth == 0) alpha = true;
            if (visible) {
                const SampledSpectrum le = scene_.emitted(*hit, ray.direction, w);
                if (!le.is_black()) {
                    const double p_emitter =
                        use_nee_ && !last_delta ? scene_.emitter_pdf(last_point, *hit, ray.direction) : 0.0;
                    radiance += weighted(beta, ratio, le, last_delta, last_pdf_hero, last_ratio_sum, p_emitter);
                }
            }
            if (settings_.max_depth >= 0 && depth + 1 >= settings_.max_depth) break;
            const Material* material = scene_.material(hit->shape);
            if (!material) break;  // emitters without a BSDF absorb

            const Frame frame = hit->shading_frame();
            const Vec3 wo = frame.to_local(-ray.direction);
            const ShadingPoint sp = shading_point(*hit, frame);
            const double ratio_sum = sum(ratio);

            if (use_nee_ && material->has_continuous_part()) {
                const auto ls = sample_light(scene_, *hit, frame, *material, sp, wo, w, sampler, use_bsdf_hits_, rays);
                if (ls) {
                    double denominator = 0;
                    for (int k = 0; k < kN; ++k)
                        denominator += ratio[k] * (ls->emitter_pdf + (ls->delta || !use_bsdf_hits_ ? 0.0 : ls->bsdf_pdf[k]));
                    radiance += beta * ls->f_cos_le * (kN / denominator);
                }
            }

            const auto s = material->sample(sp, wo, w, sampler.next(), sampler.next2());
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

            if (depth + 1 >= settings_.rr_depth) {
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

private:
    // beta_j Le_j / ((1/4) (sum_k r_k + (p_emitter / p_hero) sum_k r_k,before)): see estimator.hpp.
    SampledSpectrum weighted(const SampledSpectrum& beta, const SampledSpectrum& ratio, const SampledSpectrum& le,
                             bool last_delta, double last_pdf_hero, double last_ratio_sum, double p_emitter) const {
        if (!last_delta && !use_bsdf_hits_) return SampledSpectrum(0.0);
        double denominator = sum(ratio);
        if (!last_delta && p_emitter > 0) denominator += p_emitter / last_pdf_hero * last_ratio_sum;
        return beta * le * (kN / denominator);
    }

    const Scene& scene_;
    const IntegratorSettings& settings_;
    bool use_nee_;
    bool use_bsdf_hits_;
};

}  // namespace

std::unique_ptr<RadianceEstimator> make_path_estimator(const Scene& scene) {
    return std::make_unique<PathEstimator>(scene);
}

IntegratorSettings plugins::path(Properties& props) {
    IntegratorSettings s;
    s.type = "path";
    s.max_depth = props.get_int("max_depth", s.max_depth);
    s.rr_depth = props.get_int("rr_depth", s.rr_depth);
    s.hide_emitters = props.get_bool("hide_emitters", s.hide_emitters);
    s.strategy = props.get_string("strategy", s.strategy);
    if (s.max_depth < -1 || s.max_depth == 0) props.fail_param("max_depth", "max_depth must be -1 or positive, got {}", s.max_depth);
    if (s.rr_depth < 1) props.fail_param("rr_depth", "rr_depth must be positive, got {}", s.rr_depth);
    if (s.strategy != "mis" && s.strategy != "bsdf" && s.strategy != "emitter")
        props.fail_param("strategy", "strategy must be mis, bsdf or emitter, got '{}'", s.strategy);
    return s;
}

}  // namespace surfscatter::render
