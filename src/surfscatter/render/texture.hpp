#pragma once
// Spectral textures over surface uv: a constant spectrum, Mitsuba's checkerboard and bitmap (PNG, JPEG, EXR).
#include <filesystem>
#include <memory>
#include <vector>

#include "surfscatter/render/spectrum_source.hpp"
#include "surfscatter/render/transform.hpp"

namespace surfscatter::render {

class Texture {
public:
    virtual ~Texture() = default;
    virtual SampledSpectrum eval(Vec2 uv, const SampledWavelengths& w) const = 0;
};
using TexturePtr = std::shared_ptr<const Texture>;

TexturePtr make_constant_texture(SpectrumPtr spectrum);

// Mitsuba's checkerboard: after to_uv, color0 where frac(u) > 1/2 equals frac(v) > 1/2, else color1.
TexturePtr make_checkerboard_texture(TexturePtr color0, TexturePtr color1, const Transform& to_uv);

struct BitmapOptions {
    std::filesystem::path filename;
    bool raw = false;       // false: 8-bit PNG/JPEG code values are sRGB-decoded to linear first
    bool bilinear = true;   // filter_type "bilinear" (true) or "nearest"
    bool repeat = true;     // wrap_mode "repeat" (true) or "clamp"
    Transform to_uv;
};
// Each texel becomes a bounded sigmoid spectrum (Jakob-Hanika, see spectrum/rgb_to_spectrum.hpp) times a scale
// (> 1 only for EXR texels above 1); bilinear filtering blends the texel spectra. Image row 0 is v = 0 (Mitsuba).
TexturePtr make_bitmap_texture(const BitmapOptions& options);

}  // namespace surfscatter::render
