// surfscatter pose: camera pose from an ArUco marker or a whole ChArUco / ArUco grid board in a photograph, in the
// scene frame (photo/pose.hpp), with its uncertainty, the ambiguity check, and the matching Mitsuba-style <sensor>.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "board_options.hpp"
#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::string photo;
    std::string camera;
    BoardOptions board;
    std::optional<int> marker_id;
    bool allow_ambiguous = false;
    std::string output;
};

nlohmann::json matrix_json(const cv::Matx44d& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i) rows.push_back({m(i, 0), m(i, 1), m(i, 2), m(i, 3)});
    return rows;
}
nlohmann::json vec_json(const cv::Vec3d& v) { return {v[0], v[1], v[2]}; }
nlohmann::json points_json(const std::vector<cv::Point2f>& points) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& p : points) out.push_back({p.x, p.y});
    return out;
}
// JSON has no infinity: a missing second solution is null.
nlohmann::json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// One solution: where the camera is, how it reprojects, and the same pose for OpenCV and for Mitsuba.
nlohmann::json solution_json(const photo::PoseSolution& s, const photo::CameraModel& camera) {
    const double distance = cv::norm(s.position);
    const photo::MitsubaSensor sensor = photo::mitsuba_sensor(camera, s.camera_to_world, distance);
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

struct Solved {
    photo::Pose pose;
    std::string what;  // "marker 7", "ChArUco board"
    nlohmann::json source;
    std::string note;  // printed on stderr after the summary, if not empty
};

Solved solve_marker(const photo::Photo& image, const photo::CameraModel& camera, const Options& o) {
    photo::MarkerPoseOptions options;
    options.marker_length = o.board.marker_length;
    options.dictionary = o.board.dictionary;
    options.marker_id = o.marker_id;
    const photo::MarkerPose marker = photo::estimate_marker_pose(image.rgb, camera, options);
    Solved s{marker.pose, fmt::format("marker {}", marker.marker_id), {}, {}};
    nlohmann::json candidates = nlohmann::json::array();
    for (const auto& c : marker.corners.candidates)
        candidates.push_back({{"method", c.method},
                              {"corners_px", points_json(c.corners)},
                              {"pattern_residual", c.pattern_residual ? nlohmann::json(*c.pattern_residual)
                                                                      : nlohmann::json(nullptr)}});
    s.source = {{"id", marker.marker_id},
                {"dictionary", o.board.dictionary},
                {"length_m", o.board.marker_length},
                {"markers_detected", marker.markers_detected},
                {"corners_px", points_json(marker.corners.corners)},
                {"corner_refinement", marker.corners.method},
                {"corner_candidates", candidates}};
    if (marker.corners.pattern)
        s.source["pattern_fit"] = {{"residual", marker.corners.pattern->residual},
                                   {"blur_sigma_px", marker.corners.pattern->blur_sigma_px},
                                   {"corner_std_px", marker.corners.pattern->corner_std_px}};
    if (marker.corners.method == "detector")
        s.note = "the marker's pattern could not be fitted (it or its quiet zone leaves the image) nor its edges "
                 "measured; using the detector's pixel corners, which are less accurate";
    return s;
}

Solved solve_board(const photo::Photo& image, const photo::CameraModel& camera, const Options& o) {
    const photo::BoardSpec spec = o.board.spec();
    const photo::BoardPose board = photo::estimate_board_pose(image.rgb, camera, spec);
    Solved s{board.pose, o.board.board == "grid" ? "grid board" : "ChArUco board", {}, {}};
    s.source = {{"type", o.board.board},
                {"dictionary", o.board.dictionary},
                {"marker_length_m", o.board.marker_length},
                {"markers_detected", board.markers_detected},
                {"corners_used", board.corners},
                {"frame", "origin at the board's centre, z towards the camera, y towards the board's top"}};
    if (spec.type == photo::BoardType::Grid)
        s.source["markers"] = {spec.markers_x, spec.markers_y}, s.source["marker_separation_m"] = spec.marker_separation;
    else
        s.source["squares"] = {spec.squares_x, spec.squares_y}, s.source["square_length_m"] = spec.square_length;
    return s;
}

void run(const Options& o) {
    if (o.board.board.empty() && o.board.marker_length <= 0.0)
        fail("--marker-length must be positive, got {}", o.board.marker_length);
    if (!o.board.board.empty() && o.marker_id) fail("--marker-id is for a single marker, not with --board");
    if (o.board.board.empty() && o.board.board_options_given())
        fail("--squares, --markers, --square-length and --marker-separation describe a board: give --board too");
    const photo::CameraModel camera = photo::read_camera(o.camera);
    const photo::Photo image = photo::read_photo(o.photo);
    photo::require_image_size(camera, image.rgb.size(), "photo '" + o.photo + "'");
    const Solved solved = o.board.board.empty() ? solve_marker(image, camera, o) : solve_board(image, camera, o);
    const photo::Pose& pose = solved.pose;
    if (pose.ambiguous && !o.allow_ambiguous)
        fail("the pose of {} is ambiguous: its mirror image about the line of sight, {:.1f} deg away, reprojects "
             "almost as well ({:.3g} px against {:.3g} px: ratio {:.2f}, chi-square {:.3g} at {:.2g} px image noise; "
             "rejecting it needs ratio >= {} and chi-square >= {}); photograph it larger or more obliquely, or pass "
             "--allow-ambiguous to get both poses",
             solved.what, pose.mirror_angle_deg, pose.alternative->reprojection_rms, pose.best.reprojection_rms,
             pose.ambiguity_ratio,
             pose.ambiguity_chi2, pose.uncertainty.image_noise_px, photo::kAmbiguityRatio, photo::kAmbiguityChi2);

    nlohmann::json j;
    j["photo"] = o.photo;
    j["camera_file"] = o.camera;
    j["image_size"] = {camera.image_size.width, camera.image_size.height};
    if (image.focal_length_mm) j["exif_focal_length_mm"] = *image.focal_length_mm;
    j[o.board.board.empty() ? "marker" : "board"] = solved.source;
    const nlohmann::json best = solution_json(pose.best, camera);
    for (const auto& [key, value] : best.items()) j[key] = value;
    const auto& u = pose.uncertainty;
    j["uncertainty"] = {{"position_std_m", vec_json(u.position_std_m)},
                        {"rotation_std_deg", vec_json(u.rotation_std_deg)},
                        {"image_noise_px", u.image_noise_px},
                        {"image_noise_from", u.image_noise_source},
                        {"meaning", "one standard deviation, along / about the world axes"}};
    j["ambiguity"] = {
        {"ippe_reprojection_rms_px", {pose.ippe_rms_best, pose.alternative ? nlohmann::json(pose.ippe_rms_mirror)
                                                                           : nlohmann::json(nullptr)}},
        {"mirror_is_a_minimum", pose.alternative_is_minimum},
        {"reprojection_rms_px", {pose.best.reprojection_rms, pose.alternative_is_minimum
                                                                 ? nlohmann::json(pose.alternative->reprojection_rms)
                                                                 : nlohmann::json(nullptr)}},
        {"ratio", finite_or_null(pose.ambiguity_ratio)},
        {"ratio_threshold", photo::kAmbiguityRatio},
        {"chi2", finite_or_null(pose.ambiguity_chi2)},
        {"chi2_threshold", photo::kAmbiguityChi2},
        {"mirror_angle_deg", pose.alternative ? nlohmann::json(pose.mirror_angle_deg) : nlohmann::json(nullptr)},
        {"rotation_std_deg", pose.rotation_std_deg},
        {"sigmas_threshold", photo::kAmbiguitySigmas},
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

    std::ofstream out(o.output);
    if (!out) fail("output '{}' could not be written", o.output);
    out << j.dump(2) << "\n";
    if (!out) fail("output '{}' could not be written", o.output);

    const std::string xml = best["mitsuba"]["sensor_xml"];
    std::printf("%s", xml.c_str());
    std::fprintf(stderr,
                 "surfscatter: pose: %s, camera at (%.5f, %.5f, %.5f) m +- (%.2g, %.2g, %.2g) m, %.4f m from the "
                 "origin, reprojection error %.3f px -> %s\n",
                 solved.what.c_str(), pose.best.position[0], pose.best.position[1], pose.best.position[2],
                 u.position_std_m[0], u.position_std_m[1], u.position_std_m[2], cv::norm(pose.best.position),
                 pose.best.reprojection_rms, o.output.c_str());
    if (pose.ambiguous)
        std::fprintf(stderr,
                     "surfscatter: pose: warning: the pose is ambiguous (ratio %.2f, chi-square %.3g): its mirror "
                     "image, camera at (%.5f, %.5f, %.5f) m, reprojects almost as well; both are in %s\n",
                     pose.ambiguity_ratio, pose.ambiguity_chi2, pose.alternative->position[0],
                     pose.alternative->position[1], pose.alternative->position[2], o.output.c_str());
    if (!solved.note.empty()) std::fprintf(stderr, "surfscatter: pose: note: %s\n", solved.note.c_str());
    const double aspect = camera.fy() / camera.fx();
    if (std::abs(aspect - 1.0) > 1e-3)
        std::fprintf(stderr, "surfscatter: pose: note: fy/fx = %.5f; Mitsuba assumes square pixels (fov set from fx)\n",
                     aspect);
}

const Command command("pose", [](CLI::App& app) {
    auto options = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "pose",
        "Camera pose from an ArUco marker (scene frame: marker centre = origin, marker plane z = 0, +z towards the "
        "camera, +y towards the marker's top) or from a whole ChArUco or ArUco grid board (--board; origin at the "
        "board's centre, +y towards its top). Corners fitted by the marker's pattern; both poses a plane admits "
        "solved (IPPE) and refined; exit 2 if they cannot be told apart unless --allow-ambiguous. Writes JSON with "
        "the camera-to-world transform, its uncertainty and a ready Mitsuba-style <sensor> (also printed).");
    sub->add_option("photo", options->photo, "photograph showing the marker or board")->required();
    sub->add_option("--camera", options->camera, "camera file from 'surfscatter calibrate'")->required();
    options->board.add_to(*sub, "charuco or grid (leave out for a single marker)", "");
    sub->add_option("--marker-id", options->marker_id, "marker to use when several are visible");
    sub->add_flag("--allow-ambiguous", options->allow_ambiguous,
                  "write an ambiguous pose (and its mirror image) instead of failing, with a warning");
    sub->add_option("-o,--output", options->output, "pose file to write (.json)")->required();
    sub->callback([options] { run(*options); });
});

}  // namespace
}  // namespace surfscatter::cli
