// surfscatter pose: camera pose from an ArUco marker in a photograph, in the scene frame (marker centre = origin,
// marker plane z = 0), with the matching Mitsuba-style <sensor> element.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::string photo;
    std::string camera;
    double marker_length = 0.0;
    std::string dictionary = "4X4_50";
    std::optional<int> marker_id;
    std::string output;
};

nlohmann::json matrix_json(const cv::Matx44d& m) {
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i) rows.push_back({m(i, 0), m(i, 1), m(i, 2), m(i, 3)});
    return rows;
}
nlohmann::json vec_json(const cv::Vec3d& v) { return {v[0], v[1], v[2]}; }

void run(const Options& o) {
    const photo::CameraModel camera = photo::read_camera(o.camera);
    const photo::Photo image = photo::read_photo(o.photo);
    photo::require_image_size(camera, image.rgb.size(), "photo '" + o.photo + "'");
    photo::MarkerPoseOptions options;
    options.marker_length = o.marker_length;
    options.dictionary = o.dictionary;
    options.marker_id = o.marker_id;
    const photo::MarkerPose pose = photo::estimate_marker_pose(image.rgb, camera, options);
    const double distance = cv::norm(pose.position);
    const photo::MitsubaSensor sensor = photo::mitsuba_sensor(camera, pose.camera_to_world, distance);

    nlohmann::json j;
    j["photo"] = o.photo;
    j["camera_file"] = o.camera;
    j["image_size"] = {camera.image_size.width, camera.image_size.height};
    if (image.focal_length_mm) j["exif_focal_length_mm"] = *image.focal_length_mm;
    j["marker"] = {{"id", pose.marker_id},
                   {"dictionary", o.dictionary},
                   {"length_m", o.marker_length},
                   {"markers_detected", pose.markers_detected},
                   {"corners_px", {{pose.corners[0].x, pose.corners[0].y}, {pose.corners[1].x, pose.corners[1].y},
                                   {pose.corners[2].x, pose.corners[2].y}, {pose.corners[3].x, pose.corners[3].y}}},
                   {"corner_refinement", pose.edge_refined ? "edges, linear light" : "detector (cornerSubPix)"}};
    j["reprojection_rms_px"] = pose.reprojection_rms;
    j["camera_position_m"] = vec_json(pose.position);
    j["distance_to_marker_m"] = distance;
    j["opencv"] = {{"rvec", vec_json(pose.rvec)},
                   {"tvec_m", vec_json(pose.tvec)},
                   {"camera_to_world", matrix_json(pose.camera_to_world)},
                   {"axes", "x right, y down, z forward"}};
    j["mitsuba"] = {{"fov_axis", "x"},
                    {"fov_deg", sensor.fov_x_deg},
                    {"fov_y_deg", sensor.fov_y_deg},
                    {"principal_point_offset_x", sensor.principal_point_offset_x},
                    {"principal_point_offset_y", sensor.principal_point_offset_y},
                    {"pixel_aspect_fy_over_fx", sensor.pixel_aspect},
                    {"to_world", matrix_json(sensor.to_world)},
                    {"lookat", {{"origin", vec_json(sensor.origin)}, {"target", vec_json(sensor.target)},
                                {"up", vec_json(sensor.up)}}},
                    {"axes", "x left, y up, z forward"},
                    {"sensor_xml", sensor.xml}};
    std::ofstream out(o.output);
    if (!out) fail("output '{}' could not be written", o.output);
    out << j.dump(2) << "\n";
    if (!out) fail("output '{}' could not be written", o.output);

    std::printf("%s", sensor.xml.c_str());
    std::fprintf(stderr,
                 "surfscatter: pose: marker %d, camera at (%.5f, %.5f, %.5f) m, %.4f m from the marker, "
                 "reprojection error %.3f px -> %s\n",
                 pose.marker_id, pose.position[0], pose.position[1], pose.position[2], distance,
                 pose.reprojection_rms, o.output.c_str());
    if (!pose.edge_refined)
        std::fprintf(stderr,
                     "surfscatter: pose: note: the marker's edges could not be measured (marker under 4 px per cell, "
                     "cut by the image border or occluded); using the detector's corners, which are less accurate\n");
    if (std::abs(sensor.pixel_aspect - 1.0) > 1e-3)
        std::fprintf(stderr, "surfscatter: pose: note: fy/fx = %.5f; Mitsuba assumes square pixels (fov set from fx)\n",
                     sensor.pixel_aspect);
}

const Command command("pose", [](CLI::App& app) {
    auto options = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "pose",
        "Camera pose from an ArUco marker (solvePnP IPPE_SQUARE + Levenberg-Marquardt) in the scene frame: marker "
        "centre = origin, marker plane z = 0, +z towards the camera, +y towards the marker's top. Writes JSON with the "
        "camera-to-world transform and a ready Mitsuba-style <sensor> (also printed).");
    sub->add_option("photo", options->photo, "photograph showing the marker")->required();
    sub->add_option("--camera", options->camera, "camera file from 'surfscatter calibrate'")->required();
    sub->add_option("--marker-length", options->marker_length, "marker black square edge in metres")->required();
    sub->add_option("--dictionary", options->dictionary, "ArUco dictionary")->capture_default_str();
    sub->add_option("--marker-id", options->marker_id, "marker to use when several are visible");
    sub->add_option("-o,--output", options->output, "pose file to write (.json)")->required();
    sub->callback([options] {
        require_positive(options->marker_length, "--marker-length");
        run(*options);
    });
});

}  // namespace
}  // namespace surfscatter::cli
