#include "surfscatter/photo/pose.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

std::vector<cv::Point2d> project(const std::vector<cv::Point3d>& world, const CameraModel& camera,
                                 const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
    std::vector<cv::Point2d> projected;
    cv::projectPoints(world, rvec, tvec, camera.matrix, camera.distortion, projected);
    return projected;
}

double sum_of_squares(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                      const CameraModel& camera, const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
    const auto projected = project(world, camera, rvec, tvec);
    double sum = 0.0;
    for (std::size_t i = 0; i < image.size(); ++i) {
        const double dx = projected[i].x - image[i].x, dy = projected[i].y - image[i].y;
        sum += dx * dx + dy * dy;
    }
    return sum;
}

PoseSolution as_solution(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                         const CameraModel& camera, const cv::Vec3d& rvec, const cv::Vec3d& tvec) {
    PoseSolution s;
    s.rvec = rvec, s.tvec = tvec;
    s.reprojection_rms = std::sqrt(sum_of_squares(world, image, camera, rvec, tvec) / double(image.size()));
    cv::Matx33d r;
    cv::Rodrigues(rvec, r);
    const cv::Matx33d rt = r.t();
    s.position = -(rt * tvec);
    s.camera_to_world = cv::Matx44d::eye();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) s.camera_to_world(i, j) = rt(i, j);
        s.camera_to_world(i, 3) = s.position[i];
    }
    return s;
}

PoseSolution refined_solution(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                              const CameraModel& camera, cv::Vec3d rvec, cv::Vec3d tvec) {
    cv::solvePnPRefineLM(world, image, camera.matrix, camera.distortion, rvec, tvec,
                         cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 100, 1e-12));
    return as_solution(world, image, camera, rvec, tvec);
}

double rotation_angle_deg(const cv::Vec3d& rvec_a, const cv::Vec3d& rvec_b) {
    cv::Matx33d a, b;
    cv::Rodrigues(rvec_a, a);
    cv::Rodrigues(rvec_b, b);
    return std::acos(std::clamp(0.5 * (cv::trace(a.t() * b) - 1.0), -1.0, 1.0)) * 180.0 / kPi;
}

// RMS distance between the projections of the points by two poses, pixels.
double projection_distance(const std::vector<cv::Point3d>& world, const CameraModel& camera, const PoseSolution& a,
                           const PoseSolution& b) {
    const auto pa = project(world, camera, a.rvec, a.tvec), pb = project(world, camera, b.rvec, b.tvec);
    double sum = 0;
    for (std::size_t i = 0; i < pa.size(); ++i) sum += std::pow(cv::norm(pa[i] - pb[i]), 2);
    return std::sqrt(sum / double(pa.size()));
}
// Two refined solutions closer than this (pixels) are one: Levenberg-Marquardt stops within 1e-6 px of a minimum.
constexpr double kSamePoseDistance = 1e-3;

// The projections as a function of (small rotation about the world axes, camera centre), differentiated
// numerically (central differences) at the solution.
cv::Mat pose_jacobian(const std::vector<cv::Point3d>& world, const CameraModel& camera, const PoseSolution& s) {
    cv::Matx33d r0;
    cv::Rodrigues(s.rvec, r0);
    const double scale = std::max(cv::norm(s.position), 1e-6);
    const auto projections = [&](const cv::Vec3d& rotation, const cv::Vec3d& centre) {
        cv::Matx33d dr;
        cv::Rodrigues(rotation, dr);
        const cv::Matx33d r = r0 * dr;
        cv::Vec3d rvec;
        cv::Rodrigues(r, rvec);
        return project(world, camera, rvec, -(r * centre));
    };
    cv::Mat j(2 * static_cast<int>(world.size()), 6, CV_64F);
    for (int k = 0; k < 6; ++k) {
        const double step = k < 3 ? 1e-6 : 1e-6 * scale;
        cv::Vec3d rotation(0, 0, 0), centre = s.position;
        (k < 3 ? rotation[k] : centre[k - 3]) += step;
        const auto plus = projections(rotation, centre);
        (k < 3 ? rotation[k] : centre[k - 3]) -= 2 * step;
        const auto minus = projections(rotation, centre);
        for (std::size_t i = 0; i < world.size(); ++i) {
            j.at<double>(2 * static_cast<int>(i), k) = (plus[i].x - minus[i].x) / (2 * step);
            j.at<double>(2 * static_cast<int>(i) + 1, k) = (plus[i].y - minus[i].y) / (2 * step);
        }
    }
    return j;
}

PoseUncertainty uncertainty(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                            const CameraModel& camera, const PoseSolution& s, std::optional<double> point_noise_px) {
    PoseUncertainty u;
    const int dof = 2 * static_cast<int>(world.size()) - 6;
    const double residual_sigma =
        dof > 0 ? std::sqrt(sum_of_squares(world, image, camera, s.rvec, s.tvec) / dof) : 0.0;
    u.image_noise_px = residual_sigma;
    u.image_noise_source = fmt::format("reprojection residuals ({} degrees of freedom)", dof);
    if (point_noise_px && *point_noise_px > residual_sigma) {
        u.image_noise_px = *point_noise_px;
        u.image_noise_source = "marker pattern fit";
    }
    const cv::Mat j = pose_jacobian(world, camera, s);
    cv::Mat covariance;
    cv::invert(j.t() * j, covariance, cv::DECOMP_SVD);
    covariance *= u.image_noise_px * u.image_noise_px;
    for (int k = 0; k < 3; ++k) {
        u.rotation_std_deg[k] = std::sqrt(std::max(0.0, covariance.at<double>(k, k))) * 180.0 / kPi;
        u.position_std_m[k] = std::sqrt(std::max(0.0, covariance.at<double>(k + 3, k + 3)));
    }
    return u;
}
}  // namespace

Pose solve_planar_pose(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                       const CameraModel& camera, bool square, std::optional<double> point_noise_px) {
    CV_Assert(world.size() == image.size() && world.size() >= 4);
    std::vector<cv::Mat> rvecs, tvecs;
    cv::Mat errors;
    cv::solvePnPGeneric(world, image, camera.matrix, camera.distortion, rvecs, tvecs, false,
                        square ? cv::SOLVEPNP_IPPE_SQUARE : cv::SOLVEPNP_IPPE, cv::noArray(), cv::noArray(), errors);
    if (rvecs.empty()) fail("the pose could not be solved from {} points", world.size());
    std::vector<std::size_t> order(rvecs.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    const auto error = [&](std::size_t i) { return errors.at<double>(static_cast<int>(i)); };
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return error(a) < error(b); });

    Pose pose;
    pose.points = static_cast<int>(world.size());
    pose.best = refined_solution(world, image, camera, cv::Vec3d(rvecs[order[0]]), cv::Vec3d(tvecs[order[0]]));
    pose.uncertainty = uncertainty(world, image, camera, pose.best, point_noise_px);
    pose.ippe_rms_best = error(order[0]);
    pose.ambiguity_ratio = pose.ambiguity_chi2 = std::numeric_limits<double>::infinity();
    if (order.size() > 1) {
        const cv::Vec3d rvec(rvecs[order[1]]), tvec(tvecs[order[1]]);
        pose.ippe_rms_mirror = error(order[1]);
        // Refined, the mirror often reaches the same minimum (a large, head-on or steeply seen plane has only one):
        // then there is no second pose, and it is reported as IPPE gave it.
        const PoseSolution refined = refined_solution(world, image, camera, rvec, tvec);
        pose.alternative_is_minimum = projection_distance(world, camera, pose.best, refined) > kSamePoseDistance;
        pose.alternative = pose.alternative_is_minimum ? refined : as_solution(world, image, camera, rvec, tvec);
        pose.mirror_angle_deg = rotation_angle_deg(pose.best.rvec, pose.alternative->rvec);
        if (pose.alternative_is_minimum) {
            // The refined errors of the two minima: IPPE's own are first-order approximations that, head-on, are
            // both a fraction of a pixel off while the refined pose fits to a hundredth.
            const double best = pose.best.reprojection_rms, mirror = refined.reprojection_rms;
            if (best > 0) pose.ambiguity_ratio = mirror / best;
            const double sigma = pose.uncertainty.image_noise_px;
            if (sigma > 0) pose.ambiguity_chi2 = pose.points * (mirror * mirror - best * best) / (sigma * sigma);
        }
    }
    const cv::Vec3d& r = pose.uncertainty.rotation_std_deg;
    pose.rotation_std_deg = std::sqrt(r.dot(r));
    const bool rejected = pose.ambiguity_ratio >= kAmbiguityRatio && pose.ambiguity_chi2 >= kAmbiguityChi2;
    pose.ambiguous = pose.alternative_is_minimum && !rejected &&
                     pose.mirror_angle_deg > kAmbiguitySigmas * pose.rotation_std_deg;
    return pose;
}

MarkerPose estimate_marker_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const MarkerPoseOptions& options) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    require_positive(options.marker_length, options.length_name.c_str());
    const auto dictionary = load_dictionary(options.dictionary);
    const DetectedMarkers found = detect_markers(linear_rgb, dictionary);
    const auto hint = [&] {
        const std::string h = dictionary_hint(linear_rgb, options, found.ids.size());
        return h.empty() ? h : "; " + h;
    };
    if (found.ids.empty()) fail("no ArUco marker of dictionary {} found in the image{}", options.dictionary, hint());

    std::size_t chosen = found.ids.size();
    if (options.marker_id) {
        for (std::size_t i = 0; i < found.ids.size(); ++i)
            if (found.ids[i] == *options.marker_id) chosen = i;
        if (chosen == found.ids.size())
            fail("marker {} not found (markers of dictionary {} found: {}){}", *options.marker_id, options.dictionary,
                 list_ids(found.ids), hint());
    } else {
        if (found.ids.size() > 1)
            fail("several markers found ({}); choose one with {}", list_ids(found.ids), options.id_name);
        chosen = 0;
    }

    MarkerPose marker;
    marker.marker_id = found.ids[chosen];
    marker.markers_detected = static_cast<int>(found.ids.size());
    marker.corners = refine_marker(to_linear_gray(linear_rgb), found.corners[chosen], camera,
                                   marker_cells(*dictionary, marker.marker_id));
    std::optional<double> noise;
    if (marker.corners.method == "pattern") noise = marker.corners.pattern->corner_std_px;
    marker.pose = solve_planar_pose(marker_object_points(options.marker_length), marker.corners.corners, camera, true,
                                    noise);
    if (marker.pose.ambiguous) marker.dictionary_hint = dictionary_hint(linear_rgb, options, found.ids.size());
    return marker;
}

std::string dictionary_hint(const cv::Mat& linear_rgb, const MarkerPoseOptions& options, std::size_t found) {
    static constexpr const char* kFamilies[] = {"4X4_1000",      "5X5_1000",      "6X6_1000",
                                                "7X7_1000",      "ARUCO_ORIGINAL", "APRILTAG_16H5",
                                                "APRILTAG_25H9", "APRILTAG_36H10", "APRILTAG_36H11"};
    std::string best;
    std::vector<int> best_ids;
    for (const char* family : kFamilies) {
        std::vector<int> ids = detect_markers(linear_rgb, load_dictionary(family)).ids;
        if (ids.size() > std::max(found, best_ids.size())) best = family, best_ids = std::move(ids);
    }
    if (best.empty()) return {};
    std::sort(best_ids.begin(), best_ids.end());
    if (best.ends_with("_1000")) {  // the family's smallest dictionary that holds every id
        const int largest = best_ids.back();
        const char* size = largest < 50 ? "50" : largest < 100 ? "100" : largest < 250 ? "250" : "1000";
        best = best.substr(0, best.size() - 4) + size;
    }
    if (best == options.dictionary) return {};
    return fmt::format("the photo shows {} markers of dictionary {} (ids {}), {} of {}: pass {}{}", best_ids.size(),
                       best, list_ids(best_ids), found, printable(options.dictionary), options.dictionary_name, best);
}

std::vector<cv::Point3d> board_to_scene(const BoardSpec& board, const std::vector<cv::Point3f>& opencv_points) {
    // Which way OpenCV's board y runs: along the first marker's left edge (top-left to bottom-left as printed) it
    // points down the board.
    cv::Point3f down, centre;
    if (board.type == BoardType::Grid) {
        const auto grid = make_grid_board(board);
        down = grid->objPoints[0][3] - grid->objPoints[0][0];
        cv::Point3f low = grid->objPoints[0][0], high = low;
        for (const auto& marker : grid->objPoints)
            for (const auto& p : marker)
                low = {std::min(low.x, p.x), std::min(low.y, p.y), 0}, high = {std::max(high.x, p.x), std::max(high.y, p.y), 0};
        centre = 0.5f * (low + high);
    } else {
        const auto charuco = make_charuco_board(board);
        down = charuco->objPoints[0][3] - charuco->objPoints[0][0];
        centre = {static_cast<float>(0.5 * board.squares_x * board.square_length),
                  static_cast<float>(0.5 * board.squares_y * board.square_length), 0.0f};
    }
    const double flip = down.y > 0 ? -1.0 : 1.0;  // y (and z, to stay right-handed) turned to point up and out
    std::vector<cv::Point3d> scene;
    for (const auto& p : opencv_points) scene.emplace_back(p.x - centre.x, flip * (p.y - centre.y), flip * p.z);
    return scene;
}

BoardPose estimate_board_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const BoardSpec& board) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    validate(board);
    if (board.type == BoardType::Chessboard)
        fail("a pose needs a board whose orientation can be read: --board charuco or grid, not chessboard");
    const BoardView view = detect_board(linear_rgb, board, &camera);
    if (!view.found()) fail("board not found: {}", view.problem);
    if (board.type == BoardType::Grid && view.markers_detected < kMinimumGridMarkers)
        fail("too few board corners: {} grid marker found, {} needed", view.markers_detected, kMinimumGridMarkers);
    BoardPose out;
    out.corners = static_cast<int>(view.image_points.size());
    out.markers_detected = view.markers_detected;
    out.pose = solve_planar_pose(board_to_scene(board, view.object_points), view.image_points, camera, false);
    return out;
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
