// surfscatter pose: camera pose from an ArUco marker or a whole ChArUco / ArUco grid board in a photograph, in the
// scene frame (photo/pose.hpp), with its uncertainty, the ambiguity check, and the matching Mitsuba-style <sensor>.
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "board_options.hpp"
#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose_report.hpp"

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

void run(const Options& o) {
    OutputFiles files;
    files.input(o.photo, "photo");
    files.input(o.camera, "--camera");
    files.output(o.output, "-o");
    if (!o.board.board.empty() && o.marker_id) fail("--marker-id is for a single marker, not with --board");
    if (o.board.board.empty() && o.board.board_options_given())
        fail("--squares, --markers, --square-length and --marker-separation describe a board: give --board too");
    photo::PoseTarget target;
    if (!o.board.board.empty()) target.board = o.board.spec();
    target.marker.marker_length = o.board.marker_length;
    target.marker.dictionary = o.board.dictionary;
    target.marker.marker_id = o.marker_id;
    const photo::CameraModel camera = photo::read_camera(o.camera);
    const photo::Photo image = photo::read_photo(o.photo);
    photo::PoseReport report = photo::report_pose(image, "photo '" + o.photo + "'", camera, target);
    if (!o.allow_ambiguous) photo::require_unambiguous(report, "--allow-ambiguous");

    nlohmann::json& j = report.json;
    j["photo"] = o.photo;
    j["camera_file"] = o.camera;
    files.write(o.output, j.dump(2) + "\n");
    files.commit();

    const photo::Pose& pose = report.pose;
    const std::string xml = j["mitsuba"]["sensor_xml"];
    std::printf("%s", xml.c_str());
    const auto& u = pose.uncertainty;
    std::fprintf(stderr,
                 "surfscatter: pose: %s, camera at (%.5f, %.5f, %.5f) m +- (%.2g, %.2g, %.2g) m, %.4f m from the "
                 "origin, reprojection error %.3f px -> %s\n",
                 report.what.c_str(), pose.best.position[0], pose.best.position[1], pose.best.position[2],
                 u.position_std_m[0], u.position_std_m[1], u.position_std_m[2], cv::norm(pose.best.position),
                 pose.best.reprojection_rms, printable_path(o.output).c_str());
    if (pose.ambiguous)
        std::fprintf(stderr,
                     "surfscatter: pose: warning: the pose is ambiguous (ratio %.2f, chi-square %.3g): its mirror "
                     "image, camera at (%.5f, %.5f, %.5f) m, reprojects almost as well; both are in %s\n",
                     pose.ambiguity_ratio, pose.ambiguity_chi2, pose.alternative->position[0],
                     pose.alternative->position[1], pose.alternative->position[2], printable_path(o.output).c_str());
    for (const std::string& note : report.notes) print_note("pose", note);
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
