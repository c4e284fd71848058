// Mitsuba's `direct` integrator: direct illumination only, with `emitter_samples` next-event samples and
// `bsdf_samples` BSDF samples per camera ray combined by multiple importance sampling.
//
// Supported: `shading_samples` (sets both, default 1; exclusive with the other two, as in Mitsuba),
// `emitter_samples`, `bsdf_samples` (at least one of them positive), `hide_emitters` (default false).
// Estimator: a sample of strategy s is weighted by the multi-sample balance heuristic, f Le |cos| /
// (n_emitter p_emitter + n_bsdf (1/4) sum_k p_bsdf,k), where the average over the four wavelengths k is the spectral
// MIS of estimator.hpp; delta lobes and delta emitters have one strategy only. With one sample of each it equals
// the path integrator with max_depth = 2 in expectation (tests/render/test_integrators.cpp).
// Differences from Mitsuba: the balance heuristic (Mitsuba: power heuristic); no participating media.
#include <cmath>

#include "surfscatter/render/estimator.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

double mean(const SampledSpectrum& s) { return s.average(); }

class DirectEstimator final : public RadianceEstimator {
public:
    explicit DirectEstimator(const Scene& scene) : scene_(scene), settings_(scene.integrator) {}

    SampledSpectrum li(const Ray& ray, const SampledWavelengths& w, Sampler& sampler, bool& alpha) override {
        SampledSpectrum radiance(0.0);
        alpha = !settings_.hide_emitters && scene_.has_environment();
        ++rays;
        const std::optional<Hit> hit = scene_.intersect(ray);
        if (!hit) {
            if (!settings_.hide_emitters) radiance += scene_.environment(ray.direction, w);
            return radiance;
        }
        alpha = true;
        if (!settings_.hide_emitters) radiance += scene_.emitted(*hit, ray.direction, w);
        const Material* material = scene_.material(hit->shape);
        if (!material) return radiance;
        const Frame frame = hit->shading_frame();
        const Vec3 wo = frame.to_local(-ray.direction);
        const ShadingPoint sp = shading_point(*hit, frame);
        const double n_emitter = material->has_continuous_part() ? settings_.emitter_samples : 0;
        const double n_bsdf = settings_.bsdf_samples;

        for (int i = 0; i < static_cast<int>(n_emitter); ++i) {
            const auto ls = sample_light(scene_, *hit, frame, *material, sp, wo, w, sampler, n_bsdf > 0, rays);
            if (!ls) continue;
            const double denominator = n_emitter * ls->emitter_pdf + (ls->delta ? 0.0 : n_bsdf * mean(ls->bsdf_pdf));
            radiance += ls->f_cos_le * (1 / denominator);
        }
        for (int i = 0; i < settings_.bsdf_samples; ++i) {
            const auto s = material->sample(sp, wo, w, sampler.next(), sampler.next2());
            if (!s || !(s->pdf[0] > 0)) continue;
            const Vec3 wi_world = frame.to_world(s->wi);
            ++rays;
            const std::optional<Hit> next = scene_.intersect(Ray{Scene::offset_origin(*hit, wi_world), wi_world, 0.0, 1e30});
            SampledSpectrum le;
            double p_emitter = 0;
            if (next) {
                le = scene_.emitted(*next, wi_world, w);
                if (!s->delta && n_emitter > 0) p_emitter = scene_.emitter_pdf(hit->p, *next, wi_world);
            } else {
                le = scene_.environment(wi_world, w);
                if (!s->delta && n_emitter > 0) p_emitter = scene_.environment_pdf(wi_world);
            }
            if (le.is_black()) continue;
            const double cosine = s->delta ? 1.0 : std::abs(s->wi.z);
            radiance += s->f * le * (cosine / (n_bsdf * mean(s->pdf) + n_emitter * p_emitter));
        }
        return radiance;
    }

private:
    const Scene& scene_;
    const IntegratorSettings& settings_;
};

}  // namespace

std::unique_ptr<RadianceEstimator> make_direct_estimator(const Scene& scene) {
    return std::make_unique<DirectEstimator>(scene);
}

IntegratorSettings plugins::direct(Properties& props) {
    IntegratorSettings s;
    s.type = "direct";
    if (props.has("shading_samples") && (props.has("emitter_samples") || props.has("bsdf_samples")))
        props.fail("give either shading_samples or emitter_samples/bsdf_samples, not both");
    const int shading = props.get_int("shading_samples", 1);
    s.emitter_samples = props.get_int("emitter_samples", shading);
    s.bsdf_samples = props.get_int("bsdf_samples", shading);
    s.hide_emitters = props.get_bool("hide_emitters", false);
    if (s.emitter_samples < 0 || s.bsdf_samples < 0 || s.emitter_samples + s.bsdf_samples == 0)
        props.fail("direct needs emitter_samples, bsdf_samples >= 0 and at least one sample, got {} and {}",
                   s.emitter_samples, s.bsdf_samples);
    return s;
}

}  // namespace surfscatter::render
