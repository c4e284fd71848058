#include "surfscatter/render/texture.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::render {

namespace {

Vec2 apply_uv(const Transform& t, Vec2 uv) {
    const Vec3 p = t.point({uv.x, uv.y, 0.0});
    return {p.x, p.y};
}

class ConstantTexture final : public Texture {
public:
    explicit ConstantTexture(SpectrumPtr s) : spectrum_(std::move(s)) {}
    SampledSpectrum eval(Vec2, const SampledWavelengths& w) const override { return spectrum_->eval(w); }

private:
    SpectrumPtr spectrum_;
};

class CheckerboardTexture final : public Texture {
public:
    CheckerboardTexture(TexturePtr c0, TexturePtr c1, const Transform& to_uv)
        : color0_(std::move(c0)), color1_(std::move(c1)), to_uv_(to_uv) {}
    SampledSpectrum eval(Vec2 uv_in, const SampledWavelengths& w) const override {
        const Vec2 uv = apply_uv(to_uv_, uv_in);
        const bool mu = uv.x - std::floor(uv.x) > 0.5, mv = uv.y - std::floor(uv.y) > 0.5;
        return mu == mv ? color0_->eval(uv_in, w) : color1_->eval(uv_in, w);
    }

private:
    TexturePtr color0_, color1_;
    Transform to_uv_;
};

struct Texel {
    spectrum::RgbSigmoid sigmoid;
    double scale = 1.0;
};

class BitmapTexture final : public Texture {
public:
    explicit BitmapTexture(const BitmapOptions& options) : options_(options) {
        const io::Image image = io::read_image(options.filename);
        const std::string ext = options.filename.extension().string();
        const bool encoded = !options.raw && ext != ".exr" && ext != ".EXR";
        width_ = image.width;
        height_ = image.height;
        texels_.resize(static_cast<std::size_t>(width_) * height_);
        // Photographs repeat colours: fit each distinct RGB once.
        std::map<std::array<float, 3>, std::size_t> fitted;
        std::vector<Texel> unique;
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                std::array<float, 3> rgb{};
                for (int c = 0; c < 3; ++c) rgb[static_cast<std::size_t>(c)] = image.at(x, y, image.channels == 1 ? 0 : c);
                auto [it, inserted] = fitted.emplace(rgb, unique.size());
                if (inserted) unique.push_back(fit(rgb, encoded));
                texels_[static_cast<std::size_t>(y) * width_ + x] = it->second;
            }
        palette_ = std::move(unique);
    }

    SampledSpectrum eval(Vec2 uv_in, const SampledWavelengths& w) const override {
        const Vec2 uv = apply_uv(options_.to_uv, uv_in);
        const double fx = uv.x * width_ - (options_.bilinear ? 0.5 : 0.0);
        const double fy = uv.y * height_ - (options_.bilinear ? 0.5 : 0.0);
        if (!options_.bilinear) return texel(static_cast<int>(std::floor(fx)), static_cast<int>(std::floor(fy)), w);
        const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        return texel(x0, y0, w) * ((1 - tx) * (1 - ty)) + texel(x0 + 1, y0, w) * (tx * (1 - ty)) +
               texel(x0, y0 + 1, w) * ((1 - tx) * ty) + texel(x0 + 1, y0 + 1, w) * (tx * ty);
    }

private:
    static Texel fit(const std::array<float, 3>& stored, bool encoded) {
        std::array<double, 3> rgb{};
        for (std::size_t c = 0; c < 3; ++c) {
            const double v = stored[c];
            if (!std::isfinite(v) || v < 0) fail("bitmap texel value {} is negative or not finite", v);
            rgb[c] = encoded ? spectrum::srgb_decode(v) : v;
        }
        Texel t;
        t.scale = std::max({1.0, rgb[0], rgb[1], rgb[2]});
        for (double& v : rgb) v /= t.scale;
        t.sigmoid = spectrum::fit_rgb_sigmoid(rgb);
        return t;
    }

    int wrap(int i, int n) const {
        if (options_.repeat) return ((i % n) + n) % n;
        return std::clamp(i, 0, n - 1);
    }

    SampledSpectrum texel(int x, int y, const SampledWavelengths& w) const {
        const Texel& t = palette_[texels_[static_cast<std::size_t>(wrap(y, height_)) * width_ + wrap(x, width_)]];
        SampledSpectrum s;
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i) s[i] = t.scale * t.sigmoid(w.lambda[static_cast<std::size_t>(i)]);
        return s;
    }

    BitmapOptions options_;
    int width_ = 0, height_ = 0;
    std::vector<std::size_t> texels_;
    std::vector<Texel> palette_;
};

}  // namespace

TexturePtr make_constant_texture(SpectrumPtr spectrum) { return std::make_shared<ConstantTexture>(std::move(spectrum)); }

TexturePtr make_checkerboard_texture(TexturePtr color0, TexturePtr color1, const Transform& to_uv) {
    return std::make_shared<CheckerboardTexture>(std::move(color0), std::move(color1), to_uv);
}

TexturePtr make_bitmap_texture(const BitmapOptions& options) { return std::make_shared<BitmapTexture>(options); }

}  // namespace surfscatter::render
