// Mitsuba's `twosided` BSDF adapter: a reflecting BSDF on both faces of a surface.
//
// Supported: one nested BSDF (both faces) or two (front, then back), each a <bsdf> or a <ref>. On the back face the
// directions are mirrored through the surface before the nested BSDF sees them.
// Not supported (an error, as in Mitsuba): a nested BSDF that transmits (dielectrics, mask).
// Differences: none.
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

Vec3 flip(const Vec3& v) { return {v.x, v.y, -v.z}; }

class TwoSided final : public Material {
public:
    TwoSided(MaterialPtr front, MaterialPtr back) : front_(std::move(front)), back_(std::move(back)) {}

    SampledSpectrum eval(const ShadingPoint& sp, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        if (wo.z < 0) return back_->eval(sp, flip(wi), flip(wo), w, pdf);
        return front_->eval(sp, wi, wo, w, pdf);
    }

    std::optional<MaterialSample> sample(const ShadingPoint& sp, const Vec3& wo, const SampledWavelengths& w,
                                         double u_lobe, Vec2 u) const override {
        if (wo.z >= 0) return front_->sample(sp, wo, w, u_lobe, u);
        auto s = back_->sample(sp, flip(wo), w, u_lobe, u);
        if (s) s->wi = flip(s->wi);
        return s;
    }

    bool has_continuous_part() const override { return front_->has_continuous_part() || back_->has_continuous_part(); }

private:
    MaterialPtr front_, back_;
};

}  // namespace

MaterialPtr plugins::twosided(Properties& props) {
    std::vector<MaterialPtr> nested = props.take_bsdfs();
    if (nested.size() != 1 && nested.size() != 2) props.fail("twosided needs one or two nested BSDFs, got {}", nested.size());
    for (const MaterialPtr& m : nested)
        if (m->has_transmission()) props.fail("twosided cannot wrap a BSDF that transmits light");
    return std::make_shared<TwoSided>(nested.front(), nested.back());
}

}  // namespace surfscatter::render
