// Mitsuba's `envmap` emitter: an environment at infinity from a latitude-longitude image, importance sampled.
//
// Supported: `filename` (OpenEXR, Radiance .hdr, PNG or JPEG; 8-bit images are sRGB-decoded to linear as in
// Mitsuba), `scale` (default 1), `to_world`. Mapping as Mitsuba's: a local direction (sin phi sin theta, cos theta,
// -cos phi sin theta) has u = phi / 2 pi, v = theta / pi (+y is the top row of the image); texel column x sits at
// u = (x + 1/2) / width, row y at v = y / (height - 1), and the radiance is bilinear between texels (periodic in u).
// Spectra as Mitsuba's spectral variants: each texel's RGB is upsampled at half its maximum (a smooth bounded
// sigmoid spectrum, Jakob & Hanika 2019), times twice the maximum, times D65 (normalised to Y = 1). The sigmoid
// coefficients come from a table over the two chromaticity ratios (3 x 33 x 33 fits, built once per process in
// about 0.3 s; bilinear interpolation keeps the RGB round trip within 2e-3, tests/render/test_emitters.cpp).
// Importance sampling: each cell between four texels is chosen with probability proportional to the largest
// luminance of its corners times its solid angle, then a direction uniform in (phi, cos theta) within the cell; the
// density is exact for that sampler (chi-square test in tests/render/test_emitters.cpp).
// Not supported (an error): `mis_compensation` = true, a `bitmap` object. Differences: the sampling density
// (Mitsuba: piecewise bilinear luminance), which changes noise, not the expectation.
#include <algorithm>
#include <cmath>
#include <mutex>

#include <tbb/parallel_for.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::render {

namespace {

// Sigmoid coefficients of rgb / (2 max(rgb)) (largest channel 1/2), tabulated over the ratios of the two other
// channels to the largest.
class HalfMaxSigmoidTable {
public:
    static const HalfMaxSigmoidTable& instance() {
        static const HalfMaxSigmoidTable table;
        return table;
    }

    std::array<double, 3> coefficients(const std::array<double, 3>& rgb) const {
        const int m = static_cast<int>(std::max_element(rgb.begin(), rgb.end()) - rgb.begin());
        const double peak = rgb[static_cast<std::size_t>(m)];
        const double a = std::clamp(rgb[static_cast<std::size_t>((m + 1) % 3)] / peak, 0.0, 1.0) * (kRes - 1);
        const double b = std::clamp(rgb[static_cast<std::size_t>((m + 2) % 3)] / peak, 0.0, 1.0) * (kRes - 1);
        const int i = std::min(static_cast<int>(a), kRes - 2), j = std::min(static_cast<int>(b), kRes - 2);
        const double ta = a - i, tb = b - j;
        std::array<double, 3> c{};
        for (std::size_t k = 0; k < 3; ++k)
            c[k] = (1 - ta) * (1 - tb) * at(m, i, j)[k] + ta * (1 - tb) * at(m, i + 1, j)[k] +
                   (1 - ta) * tb * at(m, i, j + 1)[k] + ta * tb * at(m, i + 1, j + 1)[k];
        return c;
    }

private:
    static constexpr int kRes = 33;

    HalfMaxSigmoidTable() : table_(3 * kRes * kRes) {
        tbb::parallel_for(0, 3 * kRes * kRes, [&](int index) {
            const int m = index / (kRes * kRes), i = (index / kRes) % kRes, j = index % kRes;
            std::array<double, 3> rgb{};
            rgb[static_cast<std::size_t>(m)] = 0.5;
            rgb[static_cast<std::size_t>((m + 1) % 3)] = 0.5 * i / (kRes - 1);
            rgb[static_cast<std::size_t>((m + 2) % 3)] = 0.5 * j / (kRes - 1);
            table_[static_cast<std::size_t>(index)] = spectrum::fit_rgb_sigmoid(rgb).c;
        });
    }
    const std::array<double, 3>& at(int m, int i, int j) const {
        return table_[static_cast<std::size_t>((m * kRes + i) * kRes + j)];
    }

    std::vector<std::array<double, 3>> table_;
};

struct Texel {
    float c0 = 0, c1 = 0, c2 = 0;  // sigmoid coefficients
    float scale = 0;               // 2 max(rgb) times the emitter's scale
    double eval(double lambda) const {
        spectrum::RgbSigmoid s;
        s.c = {c0, c1, c2};
        return scale * s(lambda);
    }
};

class EnvironmentMap final : public Emitter {
public:
    EnvironmentMap(const io::Image& image, bool encoded, double scale, const Transform& to_world)
        : width_(image.width), height_(image.height), to_world_(to_world), to_local_(to_world.inverse()) {
        if (width_ < 2 || height_ < 3) fail("the environment map needs at least 2x3 pixels, got {}x{}", width_, height_);
        texels_.resize(static_cast<std::size_t>(width_) * height_);
        std::vector<double> luminance(texels_.size());
        const HalfMaxSigmoidTable& table = HalfMaxSigmoidTable::instance();
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                std::array<double, 3> rgb{};
                for (int c = 0; c < 3; ++c) {
                    const double v = image.at(x, y, image.channels < 3 ? 0 : c);
                    if (!(v >= 0 && v <= kMaxSpectrumValue))
                        fail("texel ({}, {}) value {} is not between 0 and {:g}", x, y, v, kMaxSpectrumValue);
                    rgb[static_cast<std::size_t>(c)] = encoded ? spectrum::srgb_decode(v) : v;
                }
                const std::size_t i = static_cast<std::size_t>(y) * width_ + x;
                const double peak = std::max({rgb[0], rgb[1], rgb[2]});
                if (!(peak * scale <= kMaxSpectrumValue))
                    fail("texel ({}, {}) times scale {} is {}, beyond the {:g} a spectrum may reach", x, y, scale,
                         peak * scale, kMaxSpectrumValue);
                luminance[i] = scale * spectrum::linear_srgb_to_xyz({rgb[0], rgb[1], rgb[2]}).y;
                if (!(peak > 0)) continue;
                const auto c = table.coefficients(rgb);
                texels_[i] = {static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
                              static_cast<float>(2 * peak * scale)};
            }
        build_distribution(luminance);
    }

    std::optional<EmitterSample> sample(const Vec3&, Vec2 u, const SampledWavelengths& w) const override {
        if (!(total_ > 0)) return std::nullopt;
        // Row (marginal), then column (conditional), reusing u.x and u.y after rescaling within the chosen bin.
        const auto row_it = std::upper_bound(row_cdf_.begin(), row_cdf_.end(), u.y);
        const int row = std::clamp(static_cast<int>(row_it - row_cdf_.begin()) - 1, 0, height_ - 2);
        const double r0 = row_cdf_[static_cast<std::size_t>(row)], r1 = row_cdf_[static_cast<std::size_t>(row) + 1];
        const double v_in = r1 > r0 ? std::clamp((u.y - r0) / (r1 - r0), 0.0, 1.0) : 0.5;
        const auto first = column_cdf_.begin() + static_cast<std::ptrdiff_t>(row) * (width_ + 1);
        const auto col_it = std::upper_bound(first, first + width_ + 1, u.x);
        const int col = std::clamp(static_cast<int>(col_it - first) - 1, 0, width_ - 1);
        const double c0 = first[col], c1 = first[col + 1];
        const double u_in = c1 > c0 ? std::clamp((u.x - c0) / (c1 - c0), 0.0, 1.0) : 0.5;
        const double phi = kTwoPi * (col + 0.5 + u_in) / width_;
        const double cos0 = std::cos(kPi * row / (height_ - 1)), cos1 = std::cos(kPi * (row + 1) / (height_ - 1));
        const double cos_theta = cos0 + v_in * (cos1 - cos0);
        const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
        const Vec3 local(std::sin(phi) * sin_theta, cos_theta, -std::cos(phi) * sin_theta);
        EmitterSample s;
        s.wi = normalize(to_world_.vector(local));
        s.distance = std::numeric_limits<double>::infinity();
        s.radiance = eval_local(local, w);
        s.pdf = environment_pdf(s.wi);
        if (!(s.pdf > 0)) return std::nullopt;
        return s;
    }

    bool is_environment() const override { return true; }

    SampledSpectrum environment(const Vec3& direction, const SampledWavelengths& w) const override {
        return eval_local(normalize(to_local_.vector(direction)), w);
    }

    double environment_pdf(const Vec3& direction) const override {
        if (!(total_ > 0)) return 0.0;
        int row = 0, col = 0;
        double tx = 0, ty = 0;
        locate(normalize(to_local_.vector(direction)), col, row, tx, ty);
        const double cos0 = std::cos(kPi * row / (height_ - 1)), cos1 = std::cos(kPi * (row + 1) / (height_ - 1));
        const double cell_solid_angle = kTwoPi / width_ * (cos0 - cos1);
        return weight_[static_cast<std::size_t>(row) * width_ + col] / total_ / cell_solid_angle;
    }

private:
    // Cell (column between texel centres col and col + 1, row between texel rows row and row + 1) and the bilinear
    // weights of a local direction.
    void locate(const Vec3& d, int& col, int& row, double& tx, double& ty) const {
        double u = std::atan2(d.x, -d.z) / kTwoPi;
        u -= std::floor(u);
        const double v = std::acos(std::clamp(d.y, -1.0, 1.0)) / kPi;
        double x = u * width_ - 0.5;
        x -= width_ * std::floor(x / width_);
        col = std::min(static_cast<int>(x), width_ - 1);
        tx = x - col;
        const double y = v * (height_ - 1);
        row = std::min(static_cast<int>(y), height_ - 2);
        ty = y - row;
    }

    SampledSpectrum eval_local(const Vec3& d, const SampledWavelengths& w) const {
        int row = 0, col = 0;
        double tx = 0, ty = 0;
        locate(d, col, row, tx, ty);
        const int col1 = (col + 1) % width_;
        const Texel& t00 = texel(col, row);
        const Texel& t10 = texel(col1, row);
        const Texel& t01 = texel(col, row + 1);
        const Texel& t11 = texel(col1, row + 1);
        SampledSpectrum s;
        for (int k = 0; k < spectrum::kSpectrumSamples; ++k) {
            const double lambda = w.lambda[static_cast<std::size_t>(k)];
            const double value = (1 - ty) * ((1 - tx) * t00.eval(lambda) + tx * t10.eval(lambda)) +
                                 ty * ((1 - tx) * t01.eval(lambda) + tx * t11.eval(lambda));
            s[k] = value * d65_normalised(lambda);
        }
        return s;
    }

    const Texel& texel(int x, int y) const { return texels_[static_cast<std::size_t>(y) * width_ + x]; }

    void build_distribution(const std::vector<double>& luminance) {
        const int rows = height_ - 1;
        weight_.assign(static_cast<std::size_t>(rows) * width_, 0.0);
        column_cdf_.assign(static_cast<std::size_t>(rows) * (width_ + 1), 0.0);
        row_cdf_.assign(static_cast<std::size_t>(rows) + 1, 0.0);
        for (int row = 0; row < rows; ++row) {
            const double solid_angle = kTwoPi / width_ * (std::cos(kPi * row / rows) - std::cos(kPi * (row + 1) / rows));
            double row_sum = 0;
            for (int col = 0; col < width_; ++col) {
                const int col1 = (col + 1) % width_;
                const double peak = std::max({luminance[static_cast<std::size_t>(row) * width_ + col],
                                              luminance[static_cast<std::size_t>(row) * width_ + col1],
                                              luminance[static_cast<std::size_t>(row + 1) * width_ + col],
                                              luminance[static_cast<std::size_t>(row + 1) * width_ + col1]});
                const double wgt = peak * solid_angle;
                weight_[static_cast<std::size_t>(row) * width_ + col] = wgt;
                row_sum += wgt;
                column_cdf_[static_cast<std::size_t>(row) * (width_ + 1) + col + 1] = row_sum;
            }
            for (int col = 0; col <= width_; ++col) {
                double& c = column_cdf_[static_cast<std::size_t>(row) * (width_ + 1) + col];
                c = row_sum > 0 ? c / row_sum : static_cast<double>(col) / width_;
            }
            row_cdf_[static_cast<std::size_t>(row) + 1] = row_cdf_[static_cast<std::size_t>(row)] + row_sum;
        }
        total_ = row_cdf_.back();
        if (total_ > 0)
            for (double& c : row_cdf_) c /= total_;
    }

    int width_, height_;
    Transform to_world_, to_local_;
    std::vector<Texel> texels_;
    std::vector<double> weight_;      // per cell: largest corner luminance times solid angle
    std::vector<double> column_cdf_;  // per row, width + 1 entries
    std::vector<double> row_cdf_;
    double total_ = 0;
};

}  // namespace

EmitterPtr plugins::envmap(Properties& props) {
    if (props.has("bitmap")) props.fail_param("bitmap", "envmap: a bitmap object is not supported; give filename");
    if (props.get_bool("mis_compensation", false))
        props.fail_param("mis_compensation", "envmap: mis_compensation is not supported");
    const std::filesystem::path file = props.get_file("filename");
    const double scale = props.get_float("scale", 1.0);
    if (!(scale >= 0 && scale <= kMaxSpectrumValue))
        props.fail_param("scale", "envmap scale must be between 0 and {:g}, got {}", kMaxSpectrumValue, scale);
    const Transform to_world = props.get_transform("to_world");
    const std::string ext = io::lower_extension(file);
    const bool encoded = ext == ".png" || ext == ".jpg" || ext == ".jpeg";
    try {
        return std::make_shared<EnvironmentMap>(io::read_image(file), encoded, scale, to_world);
    } catch (const Error& e) {
        props.fail("envmap {}: {}", file.string(), e.what());
    }
}

}  // namespace surfscatter::render
