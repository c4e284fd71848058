// Mitsuba's `bitmap` texture.
//
// Supported: `filename` (PNG, JPEG, OpenEXR, Radiance .hdr), `raw` (default false: 8-bit PNG/JPEG code values are
// sRGB-decoded to linear first; true keeps them, e.g. for normal maps), `filter_type` (bilinear (default) |
// nearest), `wrap_mode` (repeat (default) | mirror | clamp), `to_uv`. Image row 0 is v = 0 (Mitsuba). Texel
// centres sit at ((x + 1/2) / width, (y + 1/2) / height).
// Spectra: each texel becomes a bounded sigmoid spectrum (Jakob & Hanika 2019, spectrum/rgb_to_spectrum.hpp) times
// a scale (> 1 only for EXR/HDR texels above 1); each distinct colour is fitted once; bilinear filtering blends the
// texel spectra. A scalar reading (eval_1: blend weights, opacity, bump height) is the luminance of the linear RGB.
// Not supported (an error): `format`, `accel`, a `bitmap` object or `data` tensor (runtime-only in Mitsuba).
// Differences: Mitsuba interpolates the sigmoid coefficients rather than the spectra, and with raw = true in its
// spectral variants refuses colour queries that surfscatter answers with the upsampled raw values.
#include <algorithm>
#include <cmath>
#include <map>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::render {

namespace {

enum class Wrap { repeat, mirror, clamp };

struct Texel {
    spectrum::RgbSigmoid sigmoid;
    double scale = 1.0;
};

class BitmapTexture final : public Texture {
public:
    BitmapTexture(const io::Image& image, bool encoded, bool bilinear, Wrap wrap, const Transform& to_uv)
        : bilinear_(bilinear), wrap_(wrap), to_uv_(to_uv), width_(image.width), height_(image.height) {
        texels_.resize(static_cast<std::size_t>(width_) * height_);
        rgb_.resize(texels_.size());
        // Photographs repeat colours: fit each distinct RGB once.
        std::map<std::array<float, 3>, std::size_t> fitted;
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                std::array<float, 3> stored{};
                for (int c = 0; c < 3; ++c) stored[static_cast<std::size_t>(c)] = image.at(x, y, image.channels < 3 ? 0 : c);
                const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
                Vec3 linear;
                for (int c = 0; c < 3; ++c) {
                    const double v = stored[static_cast<std::size_t>(c)];
                    if (!(v >= 0 && v <= kMaxSpectrumValue))
                        fail("bitmap texel ({}, {}) value {} is not between 0 and {:g}", x, y, v, kMaxSpectrumValue);
                    linear[c] = encoded ? spectrum::srgb_decode(v) : v;
                }
                rgb_[i] = linear;
                auto [it, inserted] = fitted.emplace(stored, palette_.size());
                if (inserted) palette_.push_back(fit(linear));
                texels_[i] = it->second;
            }
    }

    SampledSpectrum eval(Vec2 uv, const SampledWavelengths& w) const override {
        return filtered<SampledSpectrum>(uv, [&](std::size_t i) {
            const Texel& t = palette_[texels_[i]];
            SampledSpectrum s;
            for (int k = 0; k < spectrum::kSpectrumSamples; ++k) s[k] = t.scale * t.sigmoid(w.lambda[static_cast<std::size_t>(k)]);
            return s;
        });
    }

    double eval_1(Vec2 uv) const override {
        return filtered<double>(uv, [&](std::size_t i) { return luminance(rgb_[i]); });
    }

    Vec2 eval_1_grad(Vec2 uv_in) const override {
        if (!bilinear_) return {0, 0};
        // Derivative of the bilinear interpolation within the cell (chain rule through to_uv).
        const Vec2 uv = apply_uv_transform(to_uv_, uv_in);
        const double fx = uv.x * width_ - 0.5, fy = uv.y * height_ - 0.5;
        const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        const double v00 = luminance(rgb_[index(x0, y0)]), v10 = luminance(rgb_[index(x0 + 1, y0)]);
        const double v01 = luminance(rgb_[index(x0, y0 + 1)]), v11 = luminance(rgb_[index(x0 + 1, y0 + 1)]);
        const double du = ((v10 - v00) * (1 - ty) + (v11 - v01) * ty) * width_;
        const double dv = ((v01 - v00) * (1 - tx) + (v11 - v10) * tx) * height_;
        const Vec3 a = to_uv_.vector({1, 0, 0}), b = to_uv_.vector({0, 1, 0});
        return {du * a.x + dv * a.y, du * b.x + dv * b.y};
    }

    std::optional<Vec3> eval_rgb(Vec2 uv) const override {
        return filtered<Vec3>(uv, [&](std::size_t i) { return rgb_[i]; });
    }

private:
    static double luminance(const Vec3& rgb) { return spectrum::linear_srgb_to_xyz(rgb).y; }

    static Texel fit(Vec3 rgb) {
        Texel t;
        t.scale = std::max({1.0, rgb.x, rgb.y, rgb.z});
        rgb = rgb / t.scale;
        t.sigmoid = spectrum::fit_rgb_sigmoid({rgb.x, rgb.y, rgb.z});
        return t;
    }

    int wrap(int i, int n) const {
        switch (wrap_) {
            case Wrap::repeat: return ((i % n) + n) % n;
            case Wrap::clamp: return std::clamp(i, 0, n - 1);
            case Wrap::mirror: {
                const int j = ((i % (2 * n)) + 2 * n) % (2 * n);
                return j < n ? j : 2 * n - 1 - j;
            }
        }
        return 0;
    }
    std::size_t index(int x, int y) const {
        return static_cast<std::size_t>(wrap(y, height_)) * width_ + static_cast<std::size_t>(wrap(x, width_));
    }

    template <typename T, typename Lookup>
    T filtered(Vec2 uv_in, Lookup&& lookup) const {
        const Vec2 uv = apply_uv_transform(to_uv_, uv_in);
        if (!bilinear_)
            return lookup(index(static_cast<int>(std::floor(uv.x * width_)), static_cast<int>(std::floor(uv.y * height_))));
        const double fx = uv.x * width_ - 0.5, fy = uv.y * height_ - 0.5;
        const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
        const double tx = fx - x0, ty = fy - y0;
        return lookup(index(x0, y0)) * ((1 - tx) * (1 - ty)) + lookup(index(x0 + 1, y0)) * (tx * (1 - ty)) +
               lookup(index(x0, y0 + 1)) * ((1 - tx) * ty) + lookup(index(x0 + 1, y0 + 1)) * (tx * ty);
    }

    bool bilinear_;
    Wrap wrap_;
    Transform to_uv_;
    int width_, height_;
    std::vector<std::size_t> texels_;
    std::vector<Texel> palette_;
    std::vector<Vec3> rgb_;
};

}  // namespace

TexturePtr plugins::bitmap(Properties& props) {
    for (const char* name : {"format", "accel", "bitmap", "data"})
        if (props.has(name)) props.fail_param(name, "bitmap parameter '{}' is not supported", name);
    const std::filesystem::path file = props.get_file("filename");
    const bool raw = props.get_bool("raw", false);
    const std::string filter = props.get_string("filter_type", "bilinear");
    if (filter != "bilinear" && filter != "nearest")
        props.fail_param("filter_type", "filter_type must be bilinear or nearest, got '{}'", filter);
    const std::string wrap_name = props.get_string("wrap_mode", "repeat");
    Wrap wrap = Wrap::repeat;
    if (wrap_name == "mirror") wrap = Wrap::mirror;
    else if (wrap_name == "clamp") wrap = Wrap::clamp;
    else if (wrap_name != "repeat") props.fail_param("wrap_mode", "wrap_mode must be repeat, mirror or clamp, got '{}'", wrap_name);
    const Transform to_uv = props.get_transform("to_uv");
    const std::string ext = io::lower_extension(file);
    const bool encoded = !raw && (ext == ".png" || ext == ".jpg" || ext == ".jpeg");
    try {
        return std::make_shared<BitmapTexture>(io::read_image(file), encoded, filter == "bilinear", wrap, to_uv);
    } catch (const Error& e) {
        props.fail("bitmap {}: {}", file.string(), e.what());
    }
}

}  // namespace surfscatter::render
