// ISO 16610-61 areal Gaussian filters: transmission of sinusoids against the closed form exp(-pi (alpha lc /
// lambda)^2) (and, at the finest nesting index, against the sampled kernel's aliased sum), the edges (zero-order
// end-effect correction) and masks against direct summation of the normalised convolution, S- and L-filters, and the
// default lambda_c with its standard error against the scatter of synthesised maps.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "height_test_util.hpp"
#include "surfscatter/heightmap/gaussian_filter.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::heightmap {
using surface::KCorrelation;
using surface::synthesize_surface;
using test::error_of;
namespace {

constexpr double kPi = std::numbers::pi;
const double kAlpha = std::sqrt(std::log(2.0) / kPi);

// Amplitude of cos(k.r) + i sin(k.r) in `map` over the points at least `margin` pixels from every edge (least
// squares for a cos + b sin, which are orthogonal there to ~1e-3; solved as the 2 x 2 normal equations).
double amplitude(const HeightMap& map, double kx, double ky, std::size_t margin) {
    double cc = 0, ss = 0, cs = 0, hc = 0, hs = 0;
    for (std::size_t iy = margin; iy + margin < map.ny(); ++iy)
        for (std::size_t ix = margin; ix + margin < map.nx(); ++ix) {
            const double phase = kx * double(ix) * map.spacing_x() + ky * double(iy) * map.spacing_y();
            const double c = std::cos(phase), s = std::sin(phase);
            cc += c * c, ss += s * s, cs += c * s, hc += map(ix, iy) * c, hs += map(ix, iy) * s;
        }
    const double det = cc * ss - cs * cs;
    const double a = (hc * ss - hs * cs) / det, b = (hs * cc - hc * cs) / det;
    return std::hypot(a, b);
}

HeightMap wave(std::size_t n, double spacing, double period, double angle_deg) {
    const double k = 2 * kPi / period, kx = k * std::cos(angle_deg * kPi / 180), ky = k * std::sin(angle_deg * kPi / 180);
    std::vector<double> h(n * n);
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix) h[iy * n + ix] = std::cos(kx * double(ix) * spacing + ky * double(iy) * spacing + 0.3);
    return HeightMap(n, n, spacing, spacing, std::move(h), "wave");
}

// Far from the edges the filter is the convolution with the sampled s: a sinusoid keeps exp(-pi (alpha lc/lambda)^2)
// of its amplitude, 50 % at the nesting index, along x and obliquely, to 1e-9 when s is sampled finely.
TEST(GaussianFilter, TransmissionOfSinusoidsIsTheClosedForm) {
    const double spacing = 0.5, lc = 20.0;
    const std::size_t n = 400, margin = 70;  // reach 1.61 lc = 64 pixels
    for (const double ratio : {0.5, 1.0, 2.0, 4.0})
        for (const double angle : {0.0, 30.0}) {
            const double period = ratio * lc;
            const HeightMap mean = gaussian_lowpass(wave(n, spacing, period, angle), lc);
            const double k = 2 * kPi / period;
            const double measured = amplitude(mean, k * std::cos(angle * kPi / 180), k * std::sin(angle * kPi / 180), margin);
            const double closed = std::exp(-kPi * std::pow(kAlpha * lc / period, 2));
            EXPECT_NEAR(measured, closed, 1e-9) << "period " << period << " angle " << angle;
            if (ratio == 1.0) {
                EXPECT_NEAR(measured, 0.5, 1e-9);
            }
        }
}

// At the finest nesting index (3 spacings) the sampled s aliases: its transmission is
// sum_k G(f + k / dx) / sum_k G(k / dx), G(f) = exp(-pi (alpha lc f)^2), 12 % above the closed form at lambda = lc.
TEST(GaussianFilter, TransmissionAtTheFinestNestingIndexIsTheAliasedSum) {
    const double spacing = 1.0, lc = 3.0;
    const std::size_t n = 96, margin = 8;
    auto g = [&](double f) { return std::exp(-kPi * std::pow(kAlpha * lc * f, 2)); };
    for (const double period : {3.0, 6.0, 12.0}) {
        const double f = 1.0 / period;
        double num = 0, den = 0;
        for (int k = -20; k <= 20; ++k) num += g(f + k / spacing), den += g(k / spacing);
        // Separable: along x only, the y axis contributes its own sum to both.
        const HeightMap mean = gaussian_lowpass(wave(n, spacing, period, 0.0), lc);
        EXPECT_NEAR(amplitude(mean, 2 * kPi / period, 0.0, margin), num / den, 1e-9) << period;
        if (period == 3.0) {
            EXPECT_NEAR(num / den / g(f), 1.125, 0.01);
        }
    }
    EXPECT_NE(error_of([&] { gaussian_lowpass(wave(n, spacing, 6.0, 0.0), 2.9); }).find("at least 3 pixel spacings"),
              std::string::npos);
}

// Edges: the weights renormalised over the map (ISO 16610-28's zero-order correction) keep a constant exactly and,
// for a plane h = a x, give a (x + the weighted mean distance inside the map): at the left edge the direct sum
// a sum_t t dx s(t) / sum_t s(t) over t >= 0, about a alpha lc / pi.
TEST(GaussianFilter, EdgesKeepConstantsAndBiasSlopesAsTheZeroOrderCorrection) {
    const std::size_t nx = 300, ny = 40;
    const double spacing = 0.5, lc = 20.0, a = 0.01, b = kAlpha * lc;
    std::vector<double> flat(nx * ny, 2.5), plane(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) plane[iy * nx + ix] = a * double(ix) * spacing;
    const HeightMap constant = gaussian_lowpass(HeightMap(nx, ny, spacing, spacing, flat, "flat"), lc);
    for (double h : constant.heights()) ASSERT_NEAR(h, 2.5, 1e-12);
    const HeightMap mean = gaussian_lowpass(HeightMap(nx, ny, spacing, spacing, plane, "plane"), lc);
    double num = 0, den = 0;
    for (std::size_t t = 0; t < nx; ++t) {
        const double s = std::exp(-kPi * std::pow(double(t) * spacing / b, 2));
        num += double(t) * spacing * s, den += s;
    }
    for (std::size_t iy : {std::size_t{0}, ny / 2, ny - 1}) {
        EXPECT_NEAR(mean(0, iy), a * num / den, 1e-12) << iy;
        EXPECT_NEAR(mean(nx - 1, iy), a * (double(nx - 1) * spacing - num / den), 1e-12) << iy;
        EXPECT_NEAR(mean(nx / 2, iy), a * double(nx / 2) * spacing, 1e-12) << iy;  // inside: a plane is kept
    }
    // The continuous half-Gaussian's mean distance b / pi, within the sampling's half pixel.
    EXPECT_NEAR(num / den, b / kPi, spacing);
}

// Masks and non-square pixels: the FFT's normalised convolution against the direct double sum over valid points,
// with a kernel shorter than the map and one wider than it.
TEST(GaussianFilter, MaskedNormalisedConvolutionMatchesDirectSummation) {
    const std::size_t nx = 48, ny = 40;
    const double dx = 0.3, dy = 0.4;
    std::mt19937_64 rng(7);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uniform;
    std::vector<double> h(nx * ny);
    std::vector<std::uint8_t> valid(nx * ny);
    for (std::size_t i = 0; i < h.size(); ++i) {
        h[i] = normal(rng);
        valid[i] = uniform(rng) > 0.3;
    }
    for (std::size_t iy = 10; iy < 20; ++iy)
        for (std::size_t ix = 0; ix < 12; ++ix) valid[iy * nx + ix] = 0;  // a block at the edge
    const HeightMap map(nx, ny, dx, dy, h, valid, "masked");
    for (const double lc : {2.5, 40.0}) {
        const HeightMap mean = gaussian_lowpass(map, lc);
        const double b = kAlpha * lc;
        double worst = 0;
        for (std::size_t py = 0; py < ny; ++py)
            for (std::size_t px = 0; px < nx; ++px) {
                if (!map.valid(px, py)) {
                    ASSERT_FALSE(mean.valid(px, py));
                    continue;
                }
                double num = 0, den = 0;
                for (std::size_t qy = 0; qy < ny; ++qy)
                    for (std::size_t qx = 0; qx < nx; ++qx)
                        if (map.valid(qx, qy)) {
                            const double rx = (double(px) - double(qx)) * dx, ry = (double(py) - double(qy)) * dy;
                            const double s = std::exp(-kPi * (rx * rx + ry * ry) / (b * b));
                            num += s * map(qx, qy), den += s;
                        }
                worst = std::max(worst, std::abs(mean(px, py) - num / den));
            }
        EXPECT_LT(worst, 1e-12) << "lc " << lc;
    }
}

TEST(GaussianFilter, SAndLFiltersSplitTheMapAndRefuseBadNestingIndices) {
    const HeightMap map = synthesize_surface(KCorrelation(0.05, 1.0, 3.0), {128, 96, 0.25}, 3);
    const Filtered s = s_filter(map, 1.0), l = l_filter(map, 10.0);
    for (std::size_t i = 0; i < map.size(); ++i) {
        EXPECT_NEAR(s.kept.heights()[i] + s.removed.heights()[i], map.heights()[i], 1e-12);
        EXPECT_NEAR(l.kept.heights()[i] + l.removed.heights()[i], map.heights()[i], 1e-12);
    }
    EXPECT_EQ(l.removed.heights(), gaussian_lowpass(map, 10.0).heights());
    EXPECT_EQ(s.kept.heights(), gaussian_lowpass(map, 1.0).heights());
    const std::string nan = error_of([&] { l_filter(map, std::nan("")); });
    EXPECT_NE(nan.find("lambda_c nan um for synthesized surface"), std::string::npos) << nan;
    const std::string small = error_of([&] { s_filter(map, 0.5); });
    EXPECT_NE(small.find("lambda_s 0.5 um"), std::string::npos) << small;
    EXPECT_NE(small.find("(0.75 um)"), std::string::npos) << small;
}

// sigma_relative_error is the standard error of the Hann-weighted rms: its prediction against the scatter of that
// rms over 48 synthesised maps whose few longest periods hold much of the variance (the scatter's own relative
// uncertainty is 1 / sqrt(2 x 47) = 10 %).
TEST(GaussianFilter, SigmaStandardErrorMatchesTheScatterOverSurfaces) {
    const std::size_t n = 128, maps = 48;
    const KCorrelation kc(0.05, 6.0, 2.5);  // L = 24 pixels, a fifth of the map
    double predicted = 0, sum = 0, sum2 = 0;
    for (std::size_t s = 0; s < maps; ++s) {
        const HeightMap map = synthesize_surface(kc, {n, n, 0.25}, 100 + s);
        predicted += sigma_relative_error(map) / double(maps);
        double mean = 0;
        for (double h : map.heights()) mean += h / double(map.size());
        double power = 0, weight = 0;
        for (std::size_t iy = 0; iy < n; ++iy)
            for (std::size_t ix = 0; ix < n; ++ix) {
                const double w = std::pow(std::sin(kPi * (double(ix) + 0.5) / double(n)) *
                                          std::sin(kPi * (double(iy) + 0.5) / double(n)), 2);
                power += w * w * std::pow(map(ix, iy) - mean, 2), weight += w * w;
            }
        const double rms = std::sqrt(power / weight);
        sum += rms, sum2 += rms * rms;
    }
    const double mean = sum / double(maps);
    const double scatter = std::sqrt((sum2 / double(maps) - mean * mean) * double(maps) / double(maps - 1)) / mean;
    EXPECT_GT(predicted, 0.05);
    EXPECT_NE(error_of([] { sigma_relative_error(synthesize_surface(KCorrelation(0.05, 1.0, 3.0), {64, 64, 0.25}, 1),
                                                 -1.0); }).find("must be a finite length >= 0"),
              std::string::npos);
    EXPECT_NEAR(scatter / predicted, 1.0, 0.3) << "scatter " << scatter << " predicted " << predicted;
}

// The default lambda_c: none for a map that resolves its spectrum; with long-period waviness, the longest nesting
// index of the 1-2-5 series that brings sigma's standard error to 10 %, the next longer one not.
TEST(GaussianFilter, DefaultLambdaCIsNoneWhenResolvedAndTheLongestEstimableOtherwise) {
    const HeightMap rough = synthesize_surface(KCorrelation(0.05, 0.5, 3.0), {256, 256, 0.25}, 5);
    std::string reason;
    EXPECT_EQ(default_lambda_c(rough, &reason), 0.0);
    EXPECT_NE(reason.find("no L-filter: the map resolves"), std::string::npos) << reason;
    std::vector<double> h = rough.heights();
    for (std::size_t iy = 0; iy < 256; ++iy)
        for (std::size_t ix = 0; ix < 256; ++ix)
            h[iy * 256 + ix] += 0.2 * std::sin(2 * kPi * (double(ix) + 0.6 * double(iy)) / 256.0);
    const HeightMap wavy = rough.with_heights(h);
    EXPECT_GT(sigma_relative_error(wavy), kLambdaCSigmaError);
    const double lc = default_lambda_c(wavy, &reason);
    ASSERT_GT(lc, 0.0) << reason;
    EXPECT_NE(reason.find("longest of the 1-2-5 series"), std::string::npos) << reason;
    EXPECT_LE(sigma_relative_error(l_filter(wavy, lc).kept), kLambdaCSigmaError);
    const double mantissa = lc / std::pow(10.0, std::floor(std::log10(lc) + 1e-9));
    const double next = lc * (std::abs(mantissa - 2.0) < 1e-6 ? 2.5 : 2.0);
    EXPECT_GT(sigma_relative_error(l_filter(wavy, next).kept), kLambdaCSigmaError) << lc << " " << next;
}

}  // namespace
}  // namespace surfscatter::heightmap
