#pragma once
// Lens calibration from several views of a planar board (Zhang's method through cv::calibrateCamera).
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/markers.hpp"

namespace surfscatter::photo {

inline constexpr int kMinimumCalibrationViews = 3;

// A calibration is flagged weak (CameraModel::calibration_warnings, printed by `calibrate`) when one standard
// deviation of fx, fy, cx or cy exceeds kWeakIntrinsicFraction of its value, or the board's orientations in the
// views used span less than kMinimumTiltSpanDeg (the largest angle between two views' board normals): the focal
// length is then poorly determined (Zhang's method needs the board seen tilted in different directions).
inline constexpr double kWeakIntrinsicFraction = 0.01;
inline constexpr double kMinimumTiltSpanDeg = 20.0;

struct CalibrationInput {
    std::string name;  // how errors refer to the view (its file name)
    cv::Mat linear_rgb;  // CV_32FC3 linear light (read_photo)
};

struct CalibrationResult {
    CameraModel camera;
    std::vector<std::string> used;       // views where the board was found
    std::vector<std::string> rejected;   // views where it was not
    std::vector<double> per_view_rms;    // pixels, same order as `used`
    double tilt_span_deg = 0.0;          // largest angle between the board normals of two views used
};

// Detects the board in every view, rejects the views without it and calibrates intrinsics and distortion
// k1 k2 p1 p2, and k3 if `fit_k3` (off by default: unless the views reach well into the image corners, k3 is
// poorly constrained and extrapolates badly there; on for wide-angle lenses). Throws Error if the views differ in size or fewer than kMinimumCalibrationViews remain
// (naming the rejected ones); a grid board is refused (its markers' corners need the camera being calibrated).
CalibrationResult calibrate_camera(const std::vector<CalibrationInput>& views, const BoardSpec& board,
                                   bool fit_k3 = false);

}  // namespace surfscatter::photo
