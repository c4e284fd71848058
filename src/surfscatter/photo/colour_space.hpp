#pragma once
// The colour-space conversions the photo pipeline needs on whole images and chart patches: the sRGB transfer
// function (IEC 61966-2-1), linear sRGB <-> CIE XYZ (D65, Y of white = 1) and Bradford chromatic adaptation.
#include <array>

#include <opencv2/core.hpp>

namespace surfscatter::photo {

using Vec3d = std::array<double, 3>;

inline constexpr Vec3d kWhiteD65{0.95047, 1.0, 1.08883};
inline constexpr Vec3d kWhiteD50{0.96422, 1.0, 0.82521};

double srgb_decode(double encoded);  // code value in [0, 1] -> linear
double srgb_encode(double linear);   // linear -> code value (not clamped; negative values are mirrored)

Vec3d linear_srgb_to_xyz(const Vec3d& rgb);
Vec3d xyz_to_linear_srgb(const Vec3d& xyz);

// Bradford von Kries adaptation of `xyz` seen under `source_white` to `target_white`.
Vec3d bradford_adapt(const Vec3d& xyz, const Vec3d& source_white, const Vec3d& target_white);

// Whole-image versions on CV_32FC3 images with channels in R, G, B order.
cv::Mat srgb_decode_image(const cv::Mat& encoded);
cv::Mat srgb_encode_image(const cv::Mat& linear);

}  // namespace surfscatter::photo
