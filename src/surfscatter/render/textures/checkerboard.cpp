// Mitsuba's `checkerboard` texture.
//
// Supported: `color0` (default 0.4), `color1` (default 0.2), each a value, spectrum, <rgb> or nested texture, and
// `to_uv`. After to_uv, color0 where frac(u) > 1/2 equals frac(v) > 1/2, else color1 (Mitsuba's rule).
// Differences: none.
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render {

namespace {

class Checkerboard final : public Texture {
public:
    Checkerboard(TexturePtr c0, TexturePtr c1, const Transform& to_uv)
        : color0_(std::move(c0)), color1_(std::move(c1)), to_uv_(to_uv) {}
    SampledSpectrum eval(Vec2 uv, const SampledWavelengths& w) const override { return pick(uv).eval(uv, w); }
    double eval_1(Vec2 uv) const override { return pick(uv).eval_1(uv); }

private:
    const Texture& pick(Vec2 uv_in) const {
        const Vec2 uv = apply_uv_transform(to_uv_, uv_in);
        const bool mu = uv.x - std::floor(uv.x) > 0.5, mv = uv.y - std::floor(uv.y) > 0.5;
        return mu == mv ? *color0_ : *color1_;
    }

    TexturePtr color0_, color1_;
    Transform to_uv_;
};

}  // namespace

TexturePtr plugins::checkerboard(Properties& props) {
    TexturePtr c0 = props.get_texture("color0", 0.4), c1 = props.get_texture("color1", 0.2);
    return std::make_shared<Checkerboard>(std::move(c0), std::move(c1), props.get_transform("to_uv"));
}

}  // namespace surfscatter::render
