#include <gtest/gtest.h>

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"
#include "surfscatter/spectrum/rgb_to_spectrum.hpp"

using namespace surfscatter;
using namespace surfscatter::spectrum;

namespace {
double max_abs_difference(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}
}  // namespace

TEST(RgbToSpectrum, RoundTripOverTheInteriorOfTheCube) {
    // 6^3 colours in [0.01, 0.99]^3: the fitted spectrum reproduces the input within 1e-4 (its own quadrature).
    const double levels[6] = {0.01, 0.05, 0.2, 0.5, 0.8, 0.99};
    double worst = 0;
    for (double r : levels)
        for (double g : levels)
            for (double b : levels) {
                const std::array<double, 3> rgb{r, g, b};
                const RgbSigmoid s = fit_rgb_sigmoid(rgb);
                worst = std::max(worst, max_abs_difference(reflectance_to_linear_srgb(s), rgb));
            }
    EXPECT_LT(worst, 1e-4);
}

TEST(RgbToSpectrum, IndependentColorimetryAgrees) {
    // spectrum -> XYZ under D65 (cie.hpp's own integration) -> linear sRGB (color.hpp): the only difference from the
    // fit's quadrature is the white point of the tabulated D65 against sRGB's, a few 1e-3 at most.
    const RegularSpectrum& d65 = cie_illuminant("D65");
    for (const std::array<double, 3> rgb : {std::array<double, 3>{0.8, 0.2, 0.1}, {0.1, 0.6, 0.3}, {0.2, 0.3, 0.9},
                                            {0.5, 0.5, 0.5}, {0.9, 0.85, 0.1}}) {
        const RgbSigmoid s = fit_rgb_sigmoid(rgb);
        const Vec3 out = xyz_to_linear_srgb(reflectance_to_xyz(s, d65));
        EXPECT_LT(max_abs_difference({out.x, out.y, out.z}, rgb), 5e-3) << rgb[0] << "," << rgb[1] << "," << rgb[2];
    }
}

TEST(RgbToSpectrum, SpectraAreBoundedAndSmooth) {
    for (const std::array<double, 3> rgb : {std::array<double, 3>{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0},
                                            {0, 0, 0}, {1, 1, 1}, {0.999, 0.001, 0.5}}) {
        const RgbSigmoid s = fit_rgb_sigmoid(rgb);
        for (double lambda = 360; lambda <= 830; lambda += 1) {
            const double v = s(lambda);
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GE(v, 0.0);
            ASSERT_LE(v, 1.0);
        }
    }
    // Saturated primaries are approached: each keeps its dominant channel.
    const auto red = reflectance_to_linear_srgb(fit_rgb_sigmoid({1, 0, 0}));
    EXPECT_GT(red[0], 0.8);
    EXPECT_LT(red[1], 0.05);
    // Greys are exactly constant spectra.
    const RgbSigmoid grey = fit_rgb_sigmoid({0.3, 0.3, 0.3});
    EXPECT_NEAR(grey(400), 0.3, 1e-12);
    EXPECT_NEAR(grey(700), 0.3, 1e-12);
}

TEST(RgbToSpectrum, RejectsOutOfRangeInput) {
    EXPECT_THROW(fit_rgb_sigmoid({1.2, 0, 0}), Error);
    EXPECT_THROW(fit_rgb_sigmoid({-0.1, 0, 0}), Error);
    EXPECT_THROW(fit_rgb_sigmoid({NAN, 0, 0}), Error);
}
