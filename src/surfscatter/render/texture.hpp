#pragma once
// Spectral textures over surface uv: constant spectra, and Mitsuba's bitmap and checkerboard (textures/*.cpp).
#include <memory>
#include <optional>

#include "surfscatter/render/spectrum_source.hpp"
#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

class Texture {
public:
    virtual ~Texture() = default;
    virtual SampledSpectrum eval(Vec2 uv, const SampledWavelengths& w) const = 0;
    // A scalar reading (a blend weight, an opacity, a bump height): Mitsuba's eval_1, the luminance Y of the linear
    // RGB (or of the spectrum under an equal-energy white; the value itself for a <float>).
    virtual double eval_1(Vec2 uv) const = 0;
    // Its derivative with respect to (u, v) (bumpmap); zero where the texture is piecewise constant.
    virtual Vec2 eval_1_grad(Vec2 /*uv*/) const { return {0, 0}; }
    // The stored linear RGB, for textures that hold one (bitmap: a normal map reads it with raw = true).
    virtual std::optional<Vec3> eval_rgb(Vec2 /*uv*/) const { return std::nullopt; }
};
using TexturePtr = std::shared_ptr<const Texture>;

TexturePtr make_constant_texture(SpectrumPtr spectrum);

inline Vec2 apply_uv_transform(const Transform& to_uv, Vec2 uv) {
    const Vec3 p = to_uv.point({uv.x, uv.y, 0.0});
    return {p.x, p.y};
}

}  // namespace surfscatter::render
