// Mitsuba's `blendbsdf`: a linear blend of two nested BSDFs, f = (1 - weight) f_0 + weight f_1.
//
// Supported: `weight` (value or texture, required, in [0, 1]; a texture is read as its scalar value, eval_1) and two
// nested BSDFs (<bsdf> or <ref>, in order). Sampling picks BSDF 1 with probability weight; the density of a
// continuous direction is the blend of both densities; a delta lobe keeps its own direction with its probability
// times the choice.
// Differences: two delta lobes in the same direction (say a conductor blended with plastic) are sampled separately
// and not summed.
#include <algorithm>

#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class BlendBsdf final : public Material {
public:
    BlendBsdf(TexturePtr weight, MaterialPtr first, MaterialPtr second)
        : weight_(std::move(weight)), first_(std::move(first)), second_(std::move(second)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        const double t = weight(sp);
        SampledSpectrum p0, p1;
        const SampledSpectrum f = first_->eval(sp, wi, wo, w, pdf ? &p0 : nullptr) * (1 - t) +
                                  second_->eval(sp, wi, wo, w, pdf ? &p1 : nullptr) * t;
        if (pdf) *pdf = p0 * (1 - t) + p1 * t;
        return f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        const double t = weight(sp);
        const bool pick_second = u_lobe < t;
        const double u_rescaled = pick_second ? u_lobe / t : (u_lobe - t) / (1 - t);
        auto s = (pick_second ? second_ : first_)->sample(sp, wo, w, std::clamp(u_rescaled, 0.0, 1.0), u);
        if (!s) return std::nullopt;
        if (s->delta) {
            const double choice = pick_second ? t : 1 - t;
            s->f *= choice;
            s->pdf *= choice;
            return s;
        }
        s->f = eval(sp, s->wi, wo, w, &s->pdf);
        if (!(s->pdf[0] > 0)) return std::nullopt;
        return s;
    }

    bool has_continuous_part() const override { return first_->has_continuous_part() || second_->has_continuous_part(); }
    bool has_transmission() const override { return first_->has_transmission() || second_->has_transmission(); }

private:
    double weight(const ShadingPoint& sp) const { return std::clamp(weight_->eval_1(sp.uv), 0.0, 1.0); }

    TexturePtr weight_;
    MaterialPtr first_, second_;
};

}  // namespace

MaterialPtr plugins::blendbsdf(Properties& props) {
    TexturePtr weight = props.get_texture_required("weight");
    std::vector<MaterialPtr> nested = props.take_bsdfs();
    if (nested.size() != 2) props.fail("blendbsdf needs exactly two nested BSDFs, got {}", nested.size());
    return std::make_shared<BlendBsdf>(std::move(weight), nested[0], nested[1]);
}

}  // namespace surfscatter::render
