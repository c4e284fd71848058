// Mitsuba's `mask` BSDF: a partly transparent surface (leaves, cut-outs). With probability 1 - opacity light passes
// straight through; otherwise the nested BSDF scatters it.
//
// Supported: `opacity` (value or texture read as its scalar value, default 0.5, in [0, 1]) and one nested BSDF.
// f = opacity f_nested plus a delta transmission of weight 1 - opacity along -wo.
// Differences: the pass-through counts as a path vertex for max_depth (Mitsuba's path integrator does the same);
// shadow rays stop at masked surfaces, as in Mitsuba's path integrator.
#include <algorithm>

#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class Mask final : public Material {
public:
    Mask(TexturePtr opacity, MaterialPtr nested) : opacity_(std::move(opacity)), nested_(std::move(nested)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        const double a = opacity(sp);
        const SampledSpectrum f = nested_->eval(sp, wi, wo, w, pdf) * a;
        if (pdf) *pdf *= a;
        return f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        const double a = opacity(sp);
        if (u_lobe >= a) {
            MaterialSample s;
            s.delta = true;
            s.wi = -wo;
            s.f = SampledSpectrum(1 - a);
            s.pdf = SampledSpectrum(1 - a);
            return s;
        }
        auto s = nested_->sample(sp, wo, w, std::clamp(u_lobe / a, 0.0, 1.0), u);
        if (!s) return std::nullopt;
        s->f *= a;
        s->pdf *= a;
        return s;
    }

    bool has_continuous_part() const override { return nested_->has_continuous_part(); }
    bool has_transmission() const override { return true; }

private:
    double opacity(const ShadingPoint& sp) const { return std::clamp(opacity_->eval_1(sp.uv), 0.0, 1.0); }

    TexturePtr opacity_;
    MaterialPtr nested_;
};

}  // namespace

MaterialPtr plugins::mask(Properties& props) {
    TexturePtr opacity = props.get_texture("opacity", 0.5);
    std::vector<MaterialPtr> nested = props.take_bsdfs();
    if (nested.size() != 1) props.fail("mask needs exactly one nested BSDF, got {}", nested.size());
    return std::make_shared<Mask>(std::move(opacity), nested[0]);
}

}  // namespace surfscatter::render
