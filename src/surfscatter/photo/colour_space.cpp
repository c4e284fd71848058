#include "surfscatter/photo/colour_space.hpp"

#include <cmath>

namespace surfscatter::photo {

namespace {
using Mat3 = std::array<std::array<double, 3>, 3>;

Vec3d multiply(const Mat3& m, const Vec3d& v) {
    return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
            m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// IEC 61966-2-1 primaries with the D65 white, rows = X, Y, Z.
constexpr Mat3 kSrgbToXyz{{{0.4124564, 0.3575761, 0.1804375},
                           {0.2126729, 0.7151522, 0.0721750},
                           {0.0193339, 0.1191920, 0.9503041}}};
constexpr Mat3 kXyzToSrgb{{{3.2404542, -1.5371385, -0.4985314},
                           {-0.9692660, 1.8760108, 0.0415560},
                           {0.0556434, -0.2040259, 1.0572252}}};
constexpr Mat3 kBradford{{{0.8951, 0.2664, -0.1614}, {-0.7502, 1.7135, 0.0367}, {0.0389, -0.0685, 1.0296}}};
constexpr Mat3 kBradfordInverse{{{0.9869929, -0.1470543, 0.1599627},
                                 {0.4323053, 0.5183603, 0.0492912},
                                 {-0.0085287, 0.0400428, 0.9684867}}};
}  // namespace

double srgb_decode(double encoded) {
    const double magnitude = std::abs(encoded);
    const double linear = magnitude <= 0.04045 ? magnitude / 12.92 : std::pow((magnitude + 0.055) / 1.055, 2.4);
    return std::copysign(linear, encoded);
}

double srgb_encode(double linear) {
    const double magnitude = std::abs(linear);
    const double encoded = magnitude <= 0.0031308 ? 12.92 * magnitude : 1.055 * std::pow(magnitude, 1.0 / 2.4) - 0.055;
    return std::copysign(encoded, linear);
}

Vec3d linear_srgb_to_xyz(const Vec3d& rgb) { return multiply(kSrgbToXyz, rgb); }
Vec3d xyz_to_linear_srgb(const Vec3d& xyz) { return multiply(kXyzToSrgb, xyz); }

Vec3d bradford_adapt(const Vec3d& xyz, const Vec3d& source_white, const Vec3d& target_white) {
    const Vec3d cone = multiply(kBradford, xyz);
    const Vec3d source = multiply(kBradford, source_white);
    const Vec3d target = multiply(kBradford, target_white);
    return multiply(kBradfordInverse,
                    {cone[0] * target[0] / source[0], cone[1] * target[1] / source[1], cone[2] * target[2] / source[2]});
}

namespace {
template <typename F>
cv::Mat map_samples(const cv::Mat& image, F f) {
    CV_Assert(image.type() == CV_32FC3);
    cv::Mat out(image.size(), CV_32FC3);
    image.forEach<cv::Vec3f>([&](const cv::Vec3f& px, const int* pos) {
        cv::Vec3f& o = out.at<cv::Vec3f>(pos[0], pos[1]);
        for (int c = 0; c < 3; ++c) o[c] = static_cast<float>(f(static_cast<double>(px[c])));
    });
    return out;
}
}  // namespace

cv::Mat srgb_decode_image(const cv::Mat& encoded) { return map_samples(encoded, srgb_decode); }
cv::Mat srgb_encode_image(const cv::Mat& linear) { return map_samples(linear, srgb_encode); }

}  // namespace surfscatter::photo
