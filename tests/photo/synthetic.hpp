#pragma once
// Synthetic photographs for the photo tests, made with OpenCV: a textured plane z = 0 seen through a pinhole camera
// with OpenCV lens distortion (exact ray casting per sub-pixel, 3x3 supersampling), ArUco markers, ChArUco and
// chess boards, and a ColorChecker chart. Nothing here is committed as an image; the tests generate it.
#include <array>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/color_checker.hpp"

namespace surfscatter::photo::synthetic {

inline constexpr int kSupersample = 3;

// World -> OpenCV camera (rvec, tvec) of a camera at `eye` looking at `target` with `up` pointing up in the image.
struct Extrinsics {
    cv::Vec3d rvec, tvec;
};
Extrinsics look_at(const cv::Vec3d& eye, const cv::Vec3d& target, const cv::Vec3d& up);

// Normalised undistorted image coordinates (x/z, y/z) of every sub-pixel of the camera's (distorted) image.
cv::Mat sub_pixel_rays(const CameraModel& camera);

// The camera's view of `texture` (CV_8UC1) lying on z = 0, centred at the origin, `width` x `height` metres, its top
// row towards +y. Background (outside the texture or behind the camera) = `background` (0-255). Returns CV_8UC1.
cv::Mat render_plane(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                     const cv::Mat& rays, const Extrinsics& pose, double background);

// An ArUco marker whose black square is `marker_length` metres, on a white square twice as wide.
struct MarkerTexture {
    cv::Mat image;
    double size = 0.0;  // metres (width = height)
};
MarkerTexture marker_texture(int id, double marker_length, const char* dictionary = "4X4_50");

// A ChArUco board or chess board with a white margin of one square; size in metres.
struct BoardTexture {
    cv::Mat image;
    double width = 0.0, height = 0.0;
};
BoardTexture charuco_texture(int squares_x, int squares_y, double square_length, double marker_length,
                             const char* dictionary = "4X4_50");
BoardTexture chessboard_texture(int squares_x, int squares_y, double square_length);

// ColorChecker chart with linear RGB `patches` (CV_32FC3 image, `size` pixels, black frame and gaps) warped onto a
// mid-grey background of `image_size`; `corners` receives the patch-grid corners (the order of color_checker.hpp).
cv::Mat chart_photo(const std::array<Vec3d, kChartPatches>& patches, cv::Size image_size,
                    const std::array<cv::Point2f, 4>& corners);

}  // namespace surfscatter::photo::synthetic
