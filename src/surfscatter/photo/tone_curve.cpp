#include "surfscatter/photo/tone_curve.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::photo {

Linearization linearization_by_name(const std::string& name) {
    if (name == "auto") return Linearization::Auto;
    if (name == "srgb") return Linearization::Srgb;
    if (name == "linear") return Linearization::Linear;
    if (name == "gamma") return Linearization::Gamma;
    if (name == "poly") return Linearization::Poly;
    fail("unknown linearisation '{}' (expected auto, srgb, linear, gamma or poly)", name);
}

std::string linearization_name(Linearization l) {
    switch (l) {
        case Linearization::Auto: return "auto";
        case Linearization::Srgb: return "srgb";
        case Linearization::Linear: return "linear";
        case Linearization::Gamma: return "gamma";
        case Linearization::Poly: return "poly";
    }
    return "?";
}

ToneCurve::ToneCurve(Linearization family, const Coefficients& coefficients,
                     const std::array<std::array<double, 2>, 3>& log_range)
    : family_(family), coefficients_(coefficients), log_range_(log_range) {
    CV_Assert(family != Linearization::Auto);
}

int ToneCurve::free_coefficients() const {
    switch (family_) {
        case Linearization::Gamma: return 1;
        case Linearization::Poly: return 3;
        default: return 0;
    }
}

double ToneCurve::operator()(int channel, double code) const {
    if (!(code > 0)) return 0.0;
    const auto& c = coefficients_[static_cast<std::size_t>(channel)];
    switch (family_) {
        case Linearization::Linear: return code;
        case Linearization::Srgb: return spectrum::srgb_decode(code);
        case Linearization::Gamma: return std::pow(code, c[0]);
        case Linearization::Poly: {
            const auto& range = log_range_[static_cast<std::size_t>(channel)];
            const auto cubic = [&](double l) { return l * (c[0] + l * (c[1] + l * c[2])); };
            const auto slope = [&](double l) { return c[0] + l * (2 * c[1] + l * 3 * c[2]); };
            const double l = std::log(code);
            // Beyond the chart's codes: the tangent in log-log space (a gamma), not the cubic.
            const double end = l < range[0] ? range[0] : l > range[1] ? range[1] : l;
            return std::exp(cubic(end) + slope(end) * (l - end));
        }
        case Linearization::Auto: break;
    }
    return code;
}

Vec3d ToneCurve::operator()(const Vec3d& codes) const {
    return {(*this)(0, codes[0]), (*this)(1, codes[1]), (*this)(2, codes[2])};
}

cv::Mat ToneCurve::apply(const cv::Mat& codes) const {
    CV_Assert(codes.type() == CV_32FC3);
    if (family_ == Linearization::Linear) return codes.clone();
    if (family_ == Linearization::Srgb) return srgb_decode_image(codes);
    cv::Mat out(codes.size(), CV_32FC3);
    codes.forEach<cv::Vec3f>([&](const cv::Vec3f& px, const int* pos) {
        cv::Vec3f& o = out.at<cv::Vec3f>(pos[0], pos[1]);
        for (int c = 0; c < 3; ++c) o[c] = static_cast<float>((*this)(c, static_cast<double>(px[c])));
    });
    return out;
}

bool ToneCurve::increasing() const {
    for (std::size_t ch = 0; ch < 3; ++ch) {
        const auto& c = coefficients_[ch];
        if (family_ == Linearization::Gamma && !(c[0] > 0)) return false;
        if (family_ != Linearization::Poly) continue;
        // The log-log slope c1 + 2 c2 L + 3 c3 L^2 must stay positive over the range (checked at its ends and at
        // the parabola's vertex when that lies inside).
        const auto& range = log_range_[ch];
        const auto slope = [&](double l) { return c[0] + l * (2 * c[1] + l * 3 * c[2]); };
        if (!(slope(range[0]) > 0) || !(slope(range[1]) > 0)) return false;
        if (c[2] != 0) {
            const double vertex = -c[1] / (3 * c[2]);
            if (vertex > range[0] && vertex < range[1] && !(slope(vertex) > 0)) return false;
        }
    }
    return true;
}

}  // namespace surfscatter::photo
