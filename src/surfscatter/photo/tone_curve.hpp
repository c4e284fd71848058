#pragma once
// Per-channel tone curves from a photograph's code values to linear light, for colour correction of 8-bit JPEGs
// and other encoded photographs (docs/PHOTO.md, "Linearisation").
//
// Families, each a function f of the normalised code value x in [0, 1] (code / (2^bits - 1)) with f(1) = 1 (the
// colour matrix carries each channel's scale):
//   linear  f(x) = x
//   srgb    f(x) = the sRGB decoding (IEC 61966-2-1)
//   gamma   f(x) = x^g, one exponent g per channel
//   poly    ln f(x) = c1 L + c2 L^2 + c3 L^3 with L = ln x, per channel (a gamma that bends: camera tone curves,
//           S-curves); outside the range of the chart's codes it continues as the gamma of its end slope, so that
//           no cubic is extrapolated.
#include <array>
#include <string>

#include <opencv2/core.hpp>

#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo {

enum class Linearization { Auto, Srgb, Linear, Gamma, Poly };
Linearization linearization_by_name(const std::string& name);  // "auto" | "srgb" | "linear" | "gamma" | "poly"
std::string linearization_name(Linearization l);

class ToneCurve {
public:
    static constexpr int kCoefficients = 3;
    using Coefficients = std::array<std::array<double, kCoefficients>, 3>;  // per channel R, G, B

    ToneCurve() = default;  // linear
    // `family` Srgb or Linear: no coefficients. Gamma: c[ch][0] = g. Poly: c1, c2, c3 and the log-code range
    // [low, high] (per channel) where the cubic applies.
    ToneCurve(Linearization family, const Coefficients& coefficients = {},
              const std::array<std::array<double, 2>, 3>& log_range = {});

    Linearization family() const { return family_; }
    const Coefficients& coefficients() const { return coefficients_; }
    const std::array<std::array<double, 2>, 3>& log_range() const { return log_range_; }
    // The number of free coefficients per channel (0, 1 or 3).
    int free_coefficients() const;

    double operator()(int channel, double code) const;
    Vec3d operator()(const Vec3d& codes) const;
    // Every sample of a CV_32FC3 image of normalised codes (R, G, B).
    cv::Mat apply(const cv::Mat& codes) const;
    // False if the curve does not rise over its log-code range (a poly fit gone wrong).
    bool increasing() const;

private:
    Linearization family_ = Linearization::Linear;
    Coefficients coefficients_{};
    std::array<std::array<double, 2>, 3> log_range_{};
};

}  // namespace surfscatter::photo
