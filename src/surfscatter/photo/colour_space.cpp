#include "surfscatter/photo/colour_space.hpp"

#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::photo {

namespace {
Vec3 to_vec(const Vec3d& v) { return {v[0], v[1], v[2]}; }
Vec3d to_array(const Vec3& v) { return {v.x, v.y, v.z}; }

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

Vec3d white_d65() { return to_array(spectrum::srgb_white_xyz()); }
Vec3d linear_srgb_to_xyz(const Vec3d& rgb) { return to_array(spectrum::linear_srgb_to_xyz(to_vec(rgb))); }
Vec3d xyz_to_linear_srgb(const Vec3d& xyz) { return to_array(spectrum::xyz_to_linear_srgb(to_vec(xyz))); }

Vec3d bradford_adapt(const Vec3d& xyz, const Vec3d& source_white, const Vec3d& target_white) {
    return to_array(spectrum::bradford_adaptation(to_vec(source_white), to_vec(target_white)) * to_vec(xyz));
}

cv::Mat srgb_decode_image(const cv::Mat& encoded) {
    return map_samples(encoded, [](double v) { return spectrum::srgb_decode(v); });
}
cv::Mat srgb_encode_image(const cv::Mat& linear) {
    return map_samples(linear, [](double v) { return spectrum::srgb_encode(v); });
}

}  // namespace surfscatter::photo
