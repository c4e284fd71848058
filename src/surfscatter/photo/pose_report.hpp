#pragma once
// A camera pose as `surfscatter pose` writes it (JSON) and surfscatter.pose (Python) returns it: the pose of a marker
// or board (pose.hpp) with both solutions for OpenCV and for Mitsuba 3, its uncertainty and the ambiguity test.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose.hpp"

namespace surfscatter::photo {

// What the pose is solved from: a ChArUco or grid board, or (without one) the single marker `marker` describes.
struct PoseTarget {
    std::optional<BoardSpec> board;
    MarkerPoseOptions marker;
};

struct PoseReport {
    Pose pose;
    std::string what;                // "marker 7", "ChArUco board", "grid board"
    nlohmann::json json;             // what `pose` writes, but the names of its input files
    std::vector<std::string> notes;  // what the user should know: less accurate corners, non-square pixels
    std::string dictionary_hint;     // a single marker's ambiguous pose: MarkerPose::dictionary_hint
};

// Solves the pose of `target` in `image` (`image_name` names it in errors: its size must be the camera's) and
// describes it. Throws Error as estimate_marker_pose and estimate_board_pose do; an ambiguous pose is returned with
// pose.ambiguous set (require_unambiguous).
PoseReport report_pose(const Photo& image, const std::string& image_name, const CameraModel& camera,
                       const PoseTarget& target);

// Throws Error explaining the ambiguity (the two solutions, the test and its thresholds) if the pose is ambiguous;
// `allow_option` names how the user accepts an ambiguous pose ("--allow-ambiguous").
void require_unambiguous(const PoseReport& report, const std::string& allow_option);

}  // namespace surfscatter::photo
