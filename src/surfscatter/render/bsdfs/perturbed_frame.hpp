#pragma once
// What bumpmap and normalmap share: the nested BSDF evaluated in a perturbed shading frame. Directions are
// transformed into that frame; f is rescaled by |cos' / cos| so that f cos in the original frame equals the nested
// f cos' (Mitsuba's BSDFs include the cosine, ours do not), and light on different sides of the two frames is
// blocked (as Mitsuba). Solid-angle densities do not change with the frame.
#include <cmath>

#include "surfscatter/render/material.hpp"

namespace surfscatter::render {

class PerturbedFrameMaterial : public Material {
public:
    explicit PerturbedFrameMaterial(MaterialPtr nested) : nested_(std::move(nested)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        const Frame f = frame(sp);
        const Vec3 pi = f.to_local(wi), po = f.to_local(wo);
        if (pi.z * wi.z <= 0 || po.z * wo.z <= 0 || wi.z == 0) {
            if (pdf) *pdf = SampledSpectrum(0.0);
            return SampledSpectrum(0.0);
        }
        return nested_->eval(sp, pi, po, w, pdf) * std::abs(pi.z / wi.z);
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        const Frame f = frame(sp);
        const Vec3 po = f.to_local(wo);
        if (po.z * wo.z <= 0) return std::nullopt;
        auto s = nested_->sample(sp, po, w, u_lobe, u);
        if (!s) return std::nullopt;
        const Vec3 wi = f.to_world(s->wi);
        if (wi.z * s->wi.z <= 0 || wi.z == 0) return std::nullopt;
        if (!s->delta) s->f *= std::abs(s->wi.z / wi.z);
        s->wi = wi;
        return s;
    }

    bool has_continuous_part() const override { return nested_->has_continuous_part(); }
    bool has_transmission() const override { return nested_->has_transmission(); }

protected:
    // The perturbed frame expressed in the unperturbed local shading frame.
    virtual Frame frame(const ShadingPoint& sp) const = 0;

private:
    MaterialPtr nested_;
};

// The frame with normal n whose first axis follows dp/du (Gram-Schmidt), as Mitsuba builds it.
inline Frame frame_from_normal_and_tangent(const Vec3& n, const Vec3& dpdu) {
    Vec3 s = dpdu - n * dot(n, dpdu);
    if (!(s.length() > 1e-12)) return Frame(n);
    s = normalize(s);
    return Frame(s, cross(n, s), n);
}

}  // namespace surfscatter::render
