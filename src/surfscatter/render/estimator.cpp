#include "surfscatter/render/estimator.hpp"

#include <cmath>

namespace surfscatter::render {

ShadingPoint shading_point(const Hit& hit, const Frame& frame) {
    ShadingPoint sp;
    sp.uv = hit.uv;
    sp.dpdu = frame.to_local(hit.dpdu);
    sp.dpdv = frame.to_local(hit.dpdv);
    return sp;
}

std::optional<LightSample> sample_light(const Scene& scene, const Hit& hit, const Frame& frame, const Material& material,
                                        const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                        Sampler& sampler, bool need_bsdf_pdf, std::uint64_t& rays) {
    const double u_choice = sampler.next();
    const Vec2 u = sampler.next2();
    const auto e = scene.sample_emitter(hit.p, u_choice, u, w);
    if (!e) return std::nullopt;
    // Light from the side the viewer is on, unless the material transmits (the geometric normal decides, so that
    // interpolated normals cannot leak light through the surface).
    const Vec3 wo_world = frame.to_world(wo);
    if (!material.has_transmission() && dot(e->wi, hit.ng) * dot(wo_world, hit.ng) <= 0) return std::nullopt;
    const Vec3 wi = frame.to_local(e->wi);
    LightSample ls;
    ls.delta = e->delta;
    ls.emitter_pdf = e->pdf;
    const bool with_pdf = need_bsdf_pdf && !e->delta;
    const SampledSpectrum f = material.eval(sp, wi, wo, w, with_pdf ? &ls.bsdf_pdf : nullptr);
    if (f.is_black()) return std::nullopt;
    ++rays;
    const Vec3 origin = Scene::offset_origin(hit, e->wi);
    const double t_max = std::isinf(e->distance) ? 1e30 : e->distance * (1 - 1e-4);
    if (scene.occluded(origin, e->wi, t_max)) return std::nullopt;
    ls.f_cos_le = f * e->radiance * std::abs(wi.z);
    return ls;
}

}  // namespace surfscatter::render
