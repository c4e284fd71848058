#include "surfscatter/photo/pose_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

namespace {

using nlohmann::json;

json matrix_json(const cv::Matx44d& m) {
    json rows = json::array();
    for (int i = 0; i < 4; ++i) rows.push_back({m(i, 0), m(i, 1), m(i, 2), m(i, 3)});
    return rows;
}
json vec_json(const cv::Vec3d& v) { return {v[0], v[1], v[2]}; }
json points_json(const std::vector<cv::Point2f>& points) {
    json out = json::array();
    for (const auto& p : points) out.push_back({p.x, p.y});
    return out;
}
// JSON has no infinity: a missing second solution is null.
json finite_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// One solution: where the camera is, how it reprojects, and the same pose for OpenCV and for Mitsuba.
json solution_json(const PoseSolution& s, const CameraModel& camera) {
    const double distance = cv::norm(s.position);
    const MitsubaSensor sensor = mitsuba_sensor(camera, s.camera_to_world, distance);
    return {{"camera_position_m", vec_json(s.position)},
            {"distance_to_origin_m", distance},
            {"reprojection_rms_px", s.reprojection_rms},
            {"opencv",
             {{"rvec", vec_json(s.rvec)},
              {"tvec_m", vec_json(s.tvec)},
              {"camera_to_world", matrix_json(s.camera_to_world)},
              {"axes", "x right, y down, z forward"}}},
            {"mitsuba",
             {{"fov_axis", "x"},
              {"fov_deg", sensor.fov_x_deg},
              {"fov_y_deg", sensor.fov_y_deg},
              {"principal_point_offset_x", sensor.principal_point_offset_x},
              {"principal_point_offset_y", sensor.principal_point_offset_y},
              {"pixel_aspect_fy_over_fx", sensor.pixel_aspect},
              {"to_world", matrix_json(sensor.to_world)},
              {"lookat", {{"origin", vec_json(sensor.origin)}, {"target", vec_json(sensor.target)},
                          {"up", vec_json(sensor.up)}}},
              {"axes", "x left, y up, z forward"},
              {"sensor_xml", sensor.xml}}}};
}

PoseReport marker_report(const Photo& image, const CameraModel& camera, const MarkerPoseOptions& options) {
    const MarkerPose marker = estimate_marker_pose(image.rgb, camera, options);
    PoseReport report{marker.pose, fmt::format("marker {}", marker.marker_id), {}, {}, marker.dictionary_hint};
    json candidates = json::array();
    for (const auto& c : marker.corners.candidates)
        candidates.push_back({{"method", c.method},
                              {"corners_px", points_json(c.corners)},
                              {"pattern_residual", c.pattern_residual ? json(*c.pattern_residual) : json(nullptr)}});
    json& source = report.json["marker"];
    source = {{"id", marker.marker_id},
              {"dictionary", options.dictionary},
              {"length_m", options.marker_length},
              {"markers_detected", marker.markers_detected},
              {"corners_px", points_json(marker.corners.corners)},
              {"corner_refinement", marker.corners.method},
              {"corner_candidates", candidates}};
    if (marker.corners.pattern)
        source["pattern_fit"] = {{"residual", marker.corners.pattern->residual},
                                 {"blur_sigma_px", marker.corners.pattern->blur_sigma_px},
                                 {"corner_std_px", marker.corners.pattern->corner_std_px}};
    if (marker.corners.method == "detector")
        report.notes.push_back("the marker's pattern could not be fitted (it or its quiet zone leaves the image) nor "
                               "its edges measured; using the detector's pixel corners, which are less accurate");
    return report;
}

PoseReport board_report(const Photo& image, const CameraModel& camera, const BoardSpec& spec) {
    const BoardPose board = estimate_board_pose(image.rgb, camera, spec);
    PoseReport report{board.pose, spec.type == BoardType::Grid ? "grid board" : "ChArUco board", {}, {}};
    json& source = report.json["board"];
    source = {{"type", board_type_name(spec.type)},
              {"dictionary", spec.dictionary},
              {"marker_length_m", spec.marker_length},
              {"markers_detected", board.markers_detected},
              {"corners_used", board.corners},
              {"frame", "origin at the board's centre, z towards the camera, y towards the board's top"}};
    if (spec.type == BoardType::Grid)
        source["markers"] = {spec.markers_x, spec.markers_y}, source["marker_separation_m"] = spec.marker_separation;
    else
        source["squares"] = {spec.squares_x, spec.squares_y}, source["square_length_m"] = spec.square_length;
    return report;
}

}  // namespace

PoseReport report_pose(const Photo& image, const std::string& image_name, const CameraModel& camera_file,
                       const PoseTarget& target) {
    const CameraModel camera = camera_for_image(camera_file, image.rgb.size(), image_name);
    PoseReport report = target.board ? board_report(image, camera, *target.board)
                                     : marker_report(image, camera, target.marker);
    const Pose& pose = report.pose;
    json& j = report.json;
    j["image_size"] = {camera.image_size.width, camera.image_size.height};
    if (image.focal_length_mm) j["exif_focal_length_mm"] = *image.focal_length_mm;
    const json best = solution_json(pose.best, camera);  // named: items() refers to it
    for (const auto& [key, value] : best.items()) j[key] = value;
    const auto& u = pose.uncertainty;
    j["uncertainty"] = {{"position_std_m", vec_json(u.position_std_m)},
                        {"rotation_std_deg", vec_json(u.rotation_std_deg)},
                        {"image_noise_px", u.image_noise_px},
                        {"image_noise_from", u.image_noise_source},
                        {"meaning", "one standard deviation, along / about the world axes"}};
    j["ambiguity"] = {
        {"ippe_reprojection_rms_px", {pose.ippe_rms_best, pose.alternative ? json(pose.ippe_rms_mirror) : json(nullptr)}},
        {"mirror_is_a_minimum", pose.alternative_is_minimum},
        {"reprojection_rms_px", {pose.best.reprojection_rms, pose.alternative_is_minimum
                                                                 ? json(pose.alternative->reprojection_rms)
                                                                 : json(nullptr)}},
        {"ratio", finite_or_null(pose.ambiguity_ratio)},
        {"ratio_threshold", kAmbiguityRatio},
        {"chi2", finite_or_null(pose.ambiguity_chi2)},
        {"chi2_threshold", kAmbiguityChi2},
        {"mirror_angle_deg", pose.alternative ? json(pose.mirror_angle_deg) : json(nullptr)},
        {"rotation_std_deg", pose.rotation_std_deg},
        {"sigmas_threshold", kAmbiguitySigmas},
        {"ambiguous", pose.ambiguous},
        {"meaning", "IPPE gives the pose and its mirror image about the line of sight, each refined; if the mirror "
                    "refines to a pose of its own it is rejected when it reprojects >= ratio_threshold times worse and "
                    "chi2 = N (e_mirror^2 - e_best^2) / image_noise^2 >= chi2_threshold; ambiguous when it is not "
                    "rejected and lies more than sigmas_threshold rotation standard deviations away"}};
    if (pose.alternative) {
        j["alternative"] = solution_json(*pose.alternative, camera);
        j["alternative"]["refined"] = pose.alternative_is_minimum;
        j["alternative"]["note"] = pose.alternative_is_minimum
                                       ? "the mirror image, refined: a pose of its own"
                                       : "the mirror image as IPPE gave it: refined it leads back to the chosen pose";
    }
    const double aspect = camera.fy() / camera.fx();
    if (std::abs(aspect - 1.0) > 1e-3)
        report.notes.push_back(
            fmt::format("fy/fx = {:.5f}; Mitsuba assumes square pixels (fov set from fx)", aspect));
    return report;
}

void require_unambiguous(const PoseReport& report, const std::string& allow_option) {
    const Pose& pose = report.pose;
    if (!pose.ambiguous) return;
    fail("the pose of {} is ambiguous: its mirror image about the line of sight, {:.1f} deg away, reprojects almost "
         "as well ({:.3g} px against {:.3g} px: ratio {:.2f}, chi-square {:.3g} at {:.2g} px image noise; rejecting it "
         "needs ratio >= {} and chi-square >= {}); photograph it larger or more obliquely, or pass {} to get both "
         "poses{}",
         report.what, pose.mirror_angle_deg, pose.alternative->reprojection_rms, pose.best.reprojection_rms,
         pose.ambiguity_ratio, pose.ambiguity_chi2, pose.uncertainty.image_noise_px, kAmbiguityRatio, kAmbiguityChi2,
         allow_option, report.dictionary_hint.empty() ? "" : "; but " + report.dictionary_hint);
}

}  // namespace surfscatter::photo
