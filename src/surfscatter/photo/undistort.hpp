#pragma once
// Removes lens distortion: the output is what an ideal pinhole camera with the same matrix K would have seen
// (same size, same K), so it matches the Mitsuba sensor of pose.hpp. Bilinear resampling (no overshoot, so linear
// radiometric data stays non-negative); pixels that map outside the photo are 0.
#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"

namespace surfscatter::photo {

// `image`: any OpenCV image of the calibrated size (typically CV_32FC3 linear RGB).
cv::Mat undistort_image(const cv::Mat& image, const CameraModel& camera);

}  // namespace surfscatter::photo
