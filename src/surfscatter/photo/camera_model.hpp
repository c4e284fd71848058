#pragma once
// A calibrated pinhole camera with OpenCV's distortion model (k1, k2, p1, p2, k3): image x to the right, y down,
// pixel centres at integer coordinates, the camera looking along +z. Stored as YAML through cv::FileStorage.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace surfscatter::photo {

struct CameraModel {
    cv::Size image_size;  // empty: not in the camera file (OpenCV's bare camera_matrix + distortion_coefficients)
    cv::Matx33d matrix = cv::Matx33d::eye();  // [fx 0 cx; 0 fy cy; 0 0 1] in pixels
    std::vector<double> distortion;           // k1 k2 p1 p2 k3 (OpenCV order)
    double rms_reprojection_error = 0.0;      // pixels, from the calibration (0 if unknown)
    int views = 0;                            // images the calibration used
    // One standard deviation of fx, fy, cx, cy and each distortion coefficient, from the calibration's covariance
    // (cv::calibrateCamera); empty if unknown.
    std::vector<double> intrinsics_std_dev;
    // Why the calibration is weak (calibration.hpp), one sentence each; empty if it is not (or unknown).
    std::vector<std::string> calibration_warnings;

    double fx() const { return matrix(0, 0); }
    double fy() const { return matrix(1, 1); }
    double cx() const { return matrix(0, 2); }
    double cy() const { return matrix(1, 2); }
};

// Writes image_width, image_height, camera_matrix, distortion_coefficients, rms_reprojection_error, views and, when
// known, intrinsics_std_dev and calibration_warnings.
void write_camera(const std::filesystem::path& path, const CameraModel& camera);
// Throws Error naming the file and the missing or bad entry. image_width and image_height are optional (both or
// neither): a file without them leaves image_size empty, to be taken from the photograph (camera_for_image).
CameraModel read_camera(const std::filesystem::path& path);

// Throws Error if an image of `size` (from `what`) does not match the calibrated image size (if it is known).
void require_image_size(const CameraModel& camera, cv::Size size, const std::string& what);
// The camera for an image of `size`: its image size if the camera file gave none, else checked by require_image_size.
CameraModel camera_for_image(const CameraModel& camera, cv::Size size, const std::string& what);

}  // namespace surfscatter::photo
