#include "surfscatter/photo/calibration.hpp"

#include <cmath>

#include <opencv2/calib3d.hpp>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

namespace {
std::string join(const std::vector<std::string>& names) {
    std::string out;
    for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
}
}  // namespace

CalibrationResult calibrate_camera(const std::vector<CalibrationInput>& views, const BoardSpec& board, bool fit_k3) {
    validate(board);
    if (views.empty()) fail("calibration needs at least {} images, got none", kMinimumCalibrationViews);
    CalibrationResult result;
    const cv::Size size = views.front().linear_rgb.size();
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;
    for (const auto& view : views) {
        if (view.linear_rgb.size() != size)
            fail("calibration image '{}' is {}x{} pixels but '{}' is {}x{}", view.name, view.linear_rgb.cols,
                 view.linear_rgb.rows, views.front().name, size.width, size.height);
        if (auto found = detect_board(view.linear_rgb, board)) {
            object_points.push_back(std::move(found->object_points));
            image_points.push_back(std::move(found->image_points));
            result.used.push_back(view.name);
        } else {
            result.rejected.push_back(view.name);
        }
    }
    if (static_cast<int>(result.used.size()) < kMinimumCalibrationViews)
        fail("calibration needs the board in at least {} images but found it in {} of {}{}", kMinimumCalibrationViews,
             result.used.size(), views.size(),
             result.rejected.empty() ? std::string() : " (not found in: " + join(result.rejected) + ")");

    cv::Mat matrix, distortion, std_intrinsics, std_extrinsics, per_view;
    std::vector<cv::Mat> rvecs, tvecs;
    const double rms = cv::calibrateCamera(
        object_points, image_points, size, matrix, distortion, rvecs, tvecs, std_intrinsics, std_extrinsics, per_view,
        fit_k3 ? 0 : cv::CALIB_FIX_K3, cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
    if (!std::isfinite(rms) || cv::checkRange(matrix) == false || cv::checkRange(distortion) == false)
        fail("calibration did not converge (views: {})", join(result.used));

    result.camera.image_size = size;
    result.camera.matrix = cv::Matx33d(matrix);
    result.camera.distortion.assign(distortion.begin<double>(), distortion.end<double>());
    result.camera.rms_reprojection_error = rms;
    result.camera.views = static_cast<int>(result.used.size());
    result.per_view_rms.assign(per_view.begin<double>(), per_view.end<double>());
    // OpenCV orders them fx fy cx cy k1 k2 p1 p2 k3 ...: the first 4 + distortion entries are this model's.
    const auto estimated = static_cast<long>(4 + result.camera.distortion.size());
    result.camera.intrinsics_std_dev.assign(std_intrinsics.begin<double>(), std_intrinsics.begin<double>() + estimated);
    return result;
}

}  // namespace surfscatter::photo
