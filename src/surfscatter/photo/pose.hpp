#pragma once
// Camera pose from one ArUco marker, and the matching Mitsuba-3-style perspective sensor.
//
// World (scene) frame: the marker's centre is the origin, the marker lies in z = 0 with +z towards the camera,
// +x along the marker's top edge to the right and +y towards its top, as the marker is printed; lengths in metres.
// OpenCV camera frame: x right, y down, z forward. Mitsuba camera frame: x left, y up, z forward, so
// to_world(Mitsuba) = to_world(OpenCV) * diag(-1, -1, 1, 1).
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"

namespace surfscatter::photo {

struct MarkerPoseOptions {
    double marker_length = 0.0;  // metres, black square edge
    std::string dictionary = "4X4_50";
    std::optional<int> marker_id;  // required when several markers are visible
};

struct MarkerPose {
    int marker_id = -1;
    int markers_detected = 0;
    std::vector<cv::Point2f> corners;   // clockwise from the marker's top-left, as used for the pose
    bool edge_refined = false;          // corners from the marker's edges in linear light (marker_corners.hpp);
                                        // false: the detector's own sub-pixel corners (marker too small or cut)
    cv::Vec3d rvec, tvec;               // world -> OpenCV camera (Rodrigues vector, metres)
    cv::Matx44d camera_to_world;        // OpenCV camera axes
    cv::Vec3d position;                 // camera centre in the world frame, metres
    double reprojection_rms = 0.0;      // pixels, over the four corners after refinement
};

// `linear_rgb`: the photograph as CV_32FC3 linear light (read_photo). Markers are detected on its display encoding
// and their corners refined on its linear luminance. Throws Error if no marker (or not the requested one) is found
// or several are found and none was chosen.
MarkerPose estimate_marker_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const MarkerPoseOptions& options);

struct MitsubaSensor {
    double fov_x_deg = 0.0;                    // fov with fov_axis = "x"
    double fov_y_deg = 0.0;                    // for information (Mitsuba derives it from fov_x and the aspect)
    double principal_point_offset_x = 0.0;     // fractions of the film width / height, Mitsuba 3 convention
    double principal_point_offset_y = 0.0;
    double pixel_aspect = 1.0;                 // fy / fx; Mitsuba assumes 1
    cv::Matx44d to_world;                      // Mitsuba camera axes -> world
    cv::Vec3d origin, target, up;              // the same transform as a lookat
    std::string xml;                           // a ready <sensor type="perspective"> element
};

// Mitsuba 3's perspective sensor generates the ray through film position (u, v) in [0,1]^2 (u right, v down) as if
// it were at (u + ppo_x, v + ppo_y) of a centred frustum, so the optical axis meets the film at
// u = 0.5 - ppo_x: ppo_x = 0.5 - (cx + 0.5) / W and ppo_y = 0.5 - (cy + 0.5) / H (OpenCV pixel centres are at
// integers, Mitsuba's at half-integers). fov_x = 2 atan(W / (2 fx)). The film size is the calibrated image size;
// the undistorted photograph (not the raw one) is what this sensor reproduces.
MitsubaSensor mitsuba_sensor(const CameraModel& camera, const cv::Matx44d& opencv_camera_to_world,
                             double target_distance);

}  // namespace surfscatter::photo
