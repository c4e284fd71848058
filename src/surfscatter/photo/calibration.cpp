#include "surfscatter/photo/calibration.hpp"

#include <algorithm>
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

// Why a calibration is weak, one sentence each (empty if it is not).
std::vector<std::string> weaknesses(const CalibrationResult& result, bool fit_k3) {
    std::vector<std::string> out;
    const auto& c = result.camera;
    const char* names[4] = {"fx", "fy", "cx", "cy"};
    const double values[4] = {c.fx(), c.fy(), c.cx(), c.cy()};
    for (std::size_t i = 0; i < 4; ++i)
        if (!(c.intrinsics_std_dev[i] <= kWeakIntrinsicFraction * std::abs(values[i])))
            out.push_back(fmt::format("{} = {:.2f} +- {:.2f} px: its standard deviation is {:.1f} % of it (limit {} %)",
                                      names[i], values[i], c.intrinsics_std_dev[i],
                                      100 * c.intrinsics_std_dev[i] / std::abs(values[i]), 100 * kWeakIntrinsicFraction));
    if (result.tilt_span_deg < kMinimumTiltSpanDeg)
        out.push_back(fmt::format("the board's orientations span only {:.1f} deg across the views (at least {} deg "
                                  "needed to pin down the focal length)",
                                  result.tilt_span_deg, kMinimumTiltSpanDeg));
    if (!out.empty())
        out.push_back(fmt::format("the calibration from {} views is weak: add views of the board tilted 20-45 deg in "
                                  "different directions and reaching the image corners{}",
                                  result.used.size(), fit_k3 ? "" : " (k3 was not fitted; a weak set of views can "
                                                                    "also give a different focal length with it)"));
    return out;
}

double tilt_span_deg(const std::vector<cv::Mat>& rvecs) {
    std::vector<cv::Vec3d> normals;
    for (const auto& rvec : rvecs) {
        cv::Matx33d r;
        cv::Rodrigues(rvec, r);
        normals.emplace_back(r(0, 2), r(1, 2), r(2, 2));
    }
    double span = 0;
    for (std::size_t i = 0; i < normals.size(); ++i)
        for (std::size_t j = i + 1; j < normals.size(); ++j)
            span = std::max(span, std::acos(std::clamp(normals[i].dot(normals[j]), -1.0, 1.0)));
    return span * 180.0 / 3.14159265358979323846;
}
}  // namespace

CalibrationResult calibrate_camera(const std::vector<CalibrationInput>& views, const BoardSpec& board, bool fit_k3) {
    validate(board);
    if (board.type == BoardType::Grid)
        fail("calibration needs a charuco or chessboard board (a grid board's marker corners are fitted through the "
             "camera being calibrated)");
    if (views.empty()) fail("calibration needs at least {} images, got none", kMinimumCalibrationViews);
    CalibrationResult result;
    const cv::Size size = views.front().linear_rgb.size();
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;
    for (const auto& view : views) {
        if (view.linear_rgb.size() != size)
            fail("calibration image '{}' is {}x{} pixels but '{}' is {}x{}", view.name, view.linear_rgb.cols,
                 view.linear_rgb.rows, views.front().name, size.width, size.height);
        if (BoardView found = detect_board(view.linear_rgb, board); found.found()) {
            object_points.push_back(std::move(found.object_points));
            image_points.push_back(std::move(found.image_points));
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
    result.tilt_span_deg = tilt_span_deg(rvecs);
    result.camera.calibration_warnings = weaknesses(result, fit_k3);
    return result;
}

}  // namespace surfscatter::photo
