#pragma once
// RGB -> smooth bounded reflectance spectrum (Jakob & Hanika 2019, "A Low-Dimensional Function Space for Efficient
// Spectral Upsampling"): s(lambda) = S(c0 t^2 + c1 t + c2), t = (lambda - 360 nm) / 470 nm, with the algebraic
// sigmoid S(x) = 1/2 + x / (2 sqrt(1 + x^2)), so 0 < s < 1 at every wavelength. The three coefficients are solved
// here (no precomputed table) by damped Gauss-Newton so that the spectrum, seen as a reflectance under D65 by the CIE
// 1931 observer and converted to linear sRGB, reproduces the input; a continuation from mid grey toward the target
// keeps the iteration in the basin of the solution. Accuracy: for linear sRGB inputs in [0.01, 0.99]^3 the round
// trip is within 1e-4 (tests/spectrum/test_rgb_to_spectrum.cpp); colours on the faces of the cube (a channel at
// exactly 0 or 1) are approached as closely as the sigmoid allows and are special-cased when all three are equal.
#include <array>
#include <cmath>

namespace surfscatter::spectrum {

inline constexpr double kSigmoidLambdaMin = 360.0, kSigmoidLambdaRange = 470.0;  // t = 0 and 1, nm

// The algebraic sigmoid S(x) above.
inline double rgb_sigmoid(double x) { return 0.5 + x / (2.0 * std::sqrt(1.0 + x * x)); }

struct RgbSigmoid {
    std::array<double, 3> c{};  // coefficients of the quadratic in t
    double operator()(double lambda_nm) const {  // inline: evaluated on every texture lookup of a render
        const double t = (lambda_nm - kSigmoidLambdaMin) / kSigmoidLambdaRange;
        return rgb_sigmoid((c[0] * t + c[1]) * t + c[2]);
    }
};

// Linear sRGB reflectance (each channel in [0, 1]) -> sigmoid coefficients. Throws Error outside [0, 1] or on NaN.
RgbSigmoid fit_rgb_sigmoid(const std::array<double, 3>& linear_srgb);

// Linear sRGB that a reflectance spectrum shows under D65 (CIE 1931 2-degree observer, 1 nm quadrature over
// 360-830 nm, normalised so that the constant spectrum 1 maps exactly to (1, 1, 1)).
std::array<double, 3> reflectance_to_linear_srgb(const RgbSigmoid& spectrum);

}  // namespace surfscatter::spectrum
