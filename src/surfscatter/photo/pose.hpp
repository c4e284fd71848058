#pragma once
// Camera pose from one ArUco marker or from a whole board, and the matching Mitsuba-3-style perspective sensor.
//
// World (scene) frame of a marker: its centre is the origin, the marker lies in z = 0 with +z towards the camera,
// +x along its top edge to the right and +y towards its top, as the marker is printed. Of a board (ChArUco or
// ArUco grid): the board's centre is the origin, z = 0 is the board with +z towards the camera, +y towards the
// board's top (the edge where its first marker is printed) and +x completing a right-handed frame (to the right as
// printed). Lengths in metres.
// OpenCV camera frame: x right, y down, z forward. Mitsuba camera frame: x left, y up, z forward, so
// to_world(Mitsuba) = to_world(OpenCV) * diag(-1, -1, 1, 1).
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/marker_corners.hpp"
#include "surfscatter/photo/markers.hpp"

namespace surfscatter::photo {

// A plane seen from one side admits two poses that project it almost alike (the "flip" ambiguity: the mirror image
// about the line of sight). IPPE gives both; each is refined by Levenberg-Marquardt. If both reach the same pose
// there is only one (a large, head-on or steeply seen plane). Otherwise, with reprojection errors e_best <= e_mirror
// over N points, the pose is ambiguous when the image does not reject the mirror and the mirror is a different pose:
//   - not rejected: e_mirror < kAmbiguityRatio e_best, or the points' noise sigma explains the difference,
//     N (e_mirror^2 - e_best^2) / sigma^2 < kAmbiguityChi2 (a likelihood-ratio test, "3 sigma"). The second test
//     matters on small markers: with four corners the residual has two degrees of freedom and e_best can be near
//     zero by chance, which makes the ratio large while the mirror still fits within the noise;
//   - different: the angle between the two orientations exceeds kAmbiguitySigmas times the pose's rotation
//     uncertainty (its standard deviations about the three axes added in quadrature).
// docs/PHOTO.md, "Pose ambiguity".
inline constexpr double kAmbiguityRatio = 2.0;
inline constexpr double kAmbiguityChi2 = 9.0;
inline constexpr double kAmbiguitySigmas = 3.0;

struct PoseSolution {
    cv::Vec3d rvec, tvec;           // world -> OpenCV camera (Rodrigues vector, metres)
    cv::Matx44d camera_to_world;    // OpenCV camera axes
    cv::Vec3d position;             // camera centre in the world frame, metres
    double reprojection_rms = 0.0;  // pixels, over the points used, after Levenberg-Marquardt refinement
};

// One standard deviation of the pose from the covariance sigma^2 (J^T J)^-1 of the reprojection (J: derivatives of
// the projected points by the camera's position and by small rotations about the world axes).
struct PoseUncertainty {
    cv::Vec3d position_std_m;     // of the camera centre along the world axes
    cv::Vec3d rotation_std_deg;   // of the camera's orientation about the world axes
    double image_noise_px = 0.0;  // sigma: per point coordinate
    std::string image_noise_source;  // how sigma was found
};

struct Pose {
    PoseSolution best;                        // the solution that reprojects better, refined
    std::optional<PoseSolution> alternative;  // the other IPPE solution (its mirror image): refined if that leads to
    bool alternative_is_minimum = false;      // a pose of its own (true), else as IPPE gave it
    double ippe_rms_best = 0.0, ippe_rms_mirror = 0.0;  // pixels, IPPE's two solutions before refinement
    double ambiguity_ratio = 0.0;             // e_mirror / e_best, refined (infinite without a second minimum)
    double ambiguity_chi2 = 0.0;              // N (e_mirror^2 - e_best^2) / sigma^2 (infinite likewise)
    double mirror_angle_deg = 0.0;            // between the best orientation and the mirror's
    double rotation_std_deg = 0.0;            // the rotation uncertainty the angle is compared with
    bool ambiguous = false;                   // the mirror is neither rejected nor within the uncertainty
    PoseUncertainty uncertainty;
    int points = 0;
};

// Pose from points on the plane z = 0 of the world frame: IPPE (SOLVEPNP_IPPE_SQUARE for a square's four corners in
// the marker order, SOLVEPNP_IPPE otherwise) gives the two candidate poses, each refined by solvePnPRefineLM.
// `point_noise_px`: a known standard deviation of the image points (e.g. from the marker pattern fit); the
// uncertainty uses the larger of it and the one the residuals show. Throws Error if no pose can be solved.
Pose solve_planar_pose(const std::vector<cv::Point3d>& world, const std::vector<cv::Point2f>& image,
                       const CameraModel& camera, bool square, std::optional<double> point_noise_px = std::nullopt);

struct MarkerPoseOptions {
    double marker_length = 0.0;  // metres, black square edge
    std::string dictionary = "4X4_50";  // a name or a file (load_dictionary)
    std::optional<int> marker_id;  // required when several markers are visible
    std::string length_name = "--marker-length";  // how messages name marker_length, dictionary and marker_id
    std::string dictionary_name = "--dictionary ";  // followed by the name in "pass --dictionary 6X6_250"
    std::string id_name = "--marker-id";
};

struct MarkerPose {
    int marker_id = -1;
    int markers_detected = 0;
    MarkerCorners corners;  // the corners used (corners.corners, in the detector's order) and the candidates
    Pose pose;
    // When the pose is ambiguous and another standard dictionary finds more markers in the photo: which, as
    // dictionary_hint() words it (a marker of the wrong dictionary is often a false detection).
    std::string dictionary_hint;
};

// `linear_rgb`: the photograph as CV_32FC3 linear light (read_photo). Markers are detected on its display encoding
// and their corners refined on its linear luminance. Throws Error if no marker (or not the requested one) is found
// or several are found and none was chosen; when no marker or not the requested one is found, the message names the
// standard dictionary that finds markers in the photo (dictionary_hint). An ambiguous pose is returned with
// `pose.ambiguous` set.
MarkerPose estimate_marker_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const MarkerPoseOptions& options);

// If another of the standard dictionaries (every family's largest: 4X4_1000 ... 7X7_1000, ARUCO_ORIGINAL, the
// AprilTag ones) finds more markers in the photo than `found` of `options.dictionary`: "the photo shows 6 markers of
// dictionary 6X6_250 (ids 1, 2, ...), 1 of 4X4_50: pass --dictionary 6X6_250", naming the smallest dictionary of the
// family that holds every id found. Empty otherwise. Detects once per dictionary (about a second on a 12-Mpixel
// photo), so it is called only after a failure.
std::string dictionary_hint(const cv::Mat& linear_rgb, const MarkerPoseOptions& options, std::size_t found);

struct BoardPose {
    int corners = 0;           // board corners the pose was solved from
    int markers_detected = 0;  // markers of the board found (ChArUco, grid)
    Pose pose;
};

// The pose of a ChArUco or grid board in the board frame above, solved from every corner found (ChArUco corners
// interpolated with the intrinsics; all four corners of every grid marker, each fitted by its pattern). Throws Error
// if the board is not found or too few corners are (ChArUco: kMinimumCharucoCorners not on one line; grid: two
// markers).
inline constexpr int kMinimumGridMarkers = 2;
BoardPose estimate_board_pose(const cv::Mat& linear_rgb, const CameraModel& camera, const BoardSpec& board);

// The board frame's points of OpenCV's board frame (which in OpenCV 4.6 has its origin at the board's top-left,
// y down as printed and z into the board): the same points relative to the board's centre, y up, z out.
std::vector<cv::Point3d> board_to_scene(const BoardSpec& board, const std::vector<cv::Point3f>& opencv_points);

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
