#include "surfscatter/photo/pose.hpp"

#include <cmath>

#include <fmt/format.h>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/marker_corners.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::string list_ids(const std::vector<int>& ids) {
    std::string out;
    for (int id : ids) out += (out.empty() ? "" : ", ") + std::to_string(id);
    return out;
}

// Corner order of cv::aruco::detectMarkers, required by SOLVEPNP_IPPE_SQUARE.
std::vector<cv::Point3d> marker_object_points(double length) {
    const double h = 0.5 * length;
    return {{-h, h, 0.0}, {h, h, 0.0}, {h, -h, 0.0}, {-h, -h, 0.0}};
}

double reprojection_rms(const std::vector<cv::Point3d>& object, const std::vector<cv::Point2f>& image,
                        const CameraModel& camera, const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
    std::vector<cv::Point2d> projected;
    cv::projectPoints(object, rvec, tvec, camera.matrix, camera.distortion, projected);
    double sum = 0.0;
    for (std::size_t i = 0; i < image.size(); ++i) {
        const double dx = projected[i].x - image[i].x, dy = projected[i].y - image[i].y;
        sum += dx * dx + dy * dy;
    }
    return std::sqrt(sum / static_cast<double>(image.size()));
}
}  // namespace

MarkerPose estimate_marker_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const MarkerPoseOptions& options) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    require_positive(options.marker_length, "--marker-length");
    const auto dictionary = dictionary_by_name(options.dictionary);
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(to_gray8(linear_rgb), dictionary, corners, ids, marker_detector_parameters());
    if (ids.empty()) fail("no ArUco marker of dictionary {} found in the image", options.dictionary);

    std::size_t chosen = ids.size();
    if (options.marker_id) {
        for (std::size_t i = 0; i < ids.size(); ++i)
            if (ids[i] == *options.marker_id) chosen = i;
        if (chosen == ids.size())
            fail("marker {} not found (markers found: {})", *options.marker_id, list_ids(ids));
    } else {
        if (ids.size() > 1) fail("several markers found ({}); choose one with --marker-id", list_ids(ids));
        chosen = 0;
    }

    MarkerPose pose;
    pose.marker_id = ids[chosen];
    pose.markers_detected = static_cast<int>(ids.size());
    pose.corners = corners[chosen];
    if (auto refined = refine_marker_corners(to_linear_gray(linear_rgb), pose.corners, camera, dictionary->markerSize + 2)) {
        pose.corners = std::move(*refined);
        pose.edge_refined = true;
    }
    const auto object = marker_object_points(options.marker_length);

    // IPPE gives the two poses a square admits; keep the one that reprojects better, then refine it.
    std::vector<cv::Mat> rvecs, tvecs;
    cv::solvePnPGeneric(object, pose.corners, camera.matrix, camera.distortion, rvecs, tvecs, false,
                        cv::SOLVEPNP_IPPE_SQUARE);
    if (rvecs.empty()) fail("marker {} found but its pose could not be solved", pose.marker_id);
    double best = INFINITY;
    for (std::size_t i = 0; i < rvecs.size(); ++i) {
        const cv::Vec3d r(rvecs[i]), t(tvecs[i]);
        const double error = reprojection_rms(object, pose.corners, camera, r, t);
        if (error < best) best = error, pose.rvec = r, pose.tvec = t;
    }
    cv::solvePnPRefineLM(object, pose.corners, camera.matrix, camera.distortion, pose.rvec, pose.tvec,
                         cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-12));
    pose.reprojection_rms = reprojection_rms(object, pose.corners, camera, pose.rvec, pose.tvec);

    cv::Matx33d r;
    cv::Rodrigues(pose.rvec, r);
    const cv::Matx33d rt = r.t();
    pose.position = -(rt * pose.tvec);
    pose.camera_to_world = cv::Matx44d::eye();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.camera_to_world(i, j) = rt(i, j);
        pose.camera_to_world(i, 3) = pose.position[i];
    }
    return pose;
}

MitsubaSensor mitsuba_sensor(const CameraModel& camera, const cv::Matx44d& opencv_camera_to_world,
                             double target_distance) {
    require_positive(target_distance, "sensor target distance");
    MitsubaSensor s;
    const double w = camera.image_size.width, h = camera.image_size.height;
    s.fov_x_deg = 2.0 * std::atan(0.5 * w / camera.fx()) * 180.0 / kPi;
    s.fov_y_deg = 2.0 * std::atan(0.5 * h / camera.fy()) * 180.0 / kPi;
    s.principal_point_offset_x = 0.5 - (camera.cx() + 0.5) / w;
    s.principal_point_offset_y = 0.5 - (camera.cy() + 0.5) / h;
    s.pixel_aspect = camera.fy() / camera.fx();
    s.to_world = opencv_camera_to_world * cv::Matx44d(-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    for (int i = 0; i < 3; ++i) {
        s.origin[i] = s.to_world(i, 3);
        s.target[i] = s.origin[i] + target_distance * s.to_world(i, 2);
        s.up[i] = s.to_world(i, 1);
    }
    const auto v = [](const cv::Vec3d& a) { return fmt::format("{:.9g}, {:.9g}, {:.9g}", a[0], a[1], a[2]); };
    s.xml = fmt::format(
        "<sensor type=\"perspective\">\n"
        "    <string name=\"fov_axis\" value=\"x\"/>\n"
        "    <float name=\"fov\" value=\"{:.9g}\"/>\n"
        "    <float name=\"principal_point_offset_x\" value=\"{:.9g}\"/>\n"
        "    <float name=\"principal_point_offset_y\" value=\"{:.9g}\"/>\n"
        "    <transform name=\"to_world\">\n"
        "        <lookat origin=\"{}\" target=\"{}\" up=\"{}\"/>\n"
        "    </transform>\n"
        "    <film type=\"hdrfilm\">\n"
        "        <integer name=\"width\" value=\"{}\"/>\n"
        "        <integer name=\"height\" value=\"{}\"/>\n"
        "    </film>\n"
        "</sensor>\n",
        s.fov_x_deg, s.principal_point_offset_x, s.principal_point_offset_y, v(s.origin), v(s.target), v(s.up),
        camera.image_size.width, camera.image_size.height);
    return s;
}

}  // namespace surfscatter::photo
