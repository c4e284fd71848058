#pragma once
// Adapters from the photo pipeline's types (std::array triples, CV_32FC3 images in R, G, B order) to the colour
// functions of surfscatter::spectrum (color.hpp: sRGB transfer function, linear sRGB <-> XYZ, Bradford).
#include <array>

#include <opencv2/core.hpp>

namespace surfscatter::photo {

using Vec3d = std::array<double, 3>;

// The white of linear sRGB (D65 as the sRGB standard defines it), Y = 1.
Vec3d white_d65();
// The ICC profile connection space white (D50, Y = 1): the white of the ColorChecker's published CIELAB.
inline constexpr Vec3d kWhiteD50{0.96422, 1.0, 0.82521};

Vec3d linear_srgb_to_xyz(const Vec3d& rgb);
Vec3d xyz_to_linear_srgb(const Vec3d& xyz);
// Bradford adaptation of `xyz` seen under `source_white` to `target_white`.
Vec3d bradford_adapt(const Vec3d& xyz, const Vec3d& source_white, const Vec3d& target_white);

// The sRGB transfer function on every sample of a CV_32FC3 image (results clipped to [0, 1]).
cv::Mat srgb_decode_image(const cv::Mat& encoded);
cv::Mat srgb_encode_image(const cv::Mat& linear);

}  // namespace surfscatter::photo
