#include "surfscatter/photo/camera_model.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

void write_camera(const std::filesystem::path& path, const CameraModel& camera) {
    cv::FileStorage fs;
    try {
        fs.open(path.string(), cv::FileStorage::WRITE);
    } catch (const cv::Exception& e) {
        fail("camera file '{}' could not be written: {}", path.string(), e.what());
    }
    if (!fs.isOpened()) fail("camera file '{}' could not be written", path.string());
    fs << "image_width" << camera.image_size.width;
    fs << "image_height" << camera.image_size.height;
    fs << "camera_matrix" << cv::Mat(camera.matrix);
    fs << "distortion_coefficients" << cv::Mat(camera.distortion).reshape(1, 1);
    fs << "rms_reprojection_error" << camera.rms_reprojection_error;
    fs << "views" << camera.views;
    if (!camera.intrinsics_std_dev.empty()) fs << "intrinsics_std_dev" << cv::Mat(camera.intrinsics_std_dev).reshape(1, 1);
}

CameraModel read_camera(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) fail("camera file '{}' does not exist", path.string());
    cv::FileStorage fs;
    try {
        fs.open(path.string(), cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
        fail("camera file '{}' is not valid YAML/XML: {}", path.string(), e.what());
    }
    if (!fs.isOpened()) fail("camera file '{}' could not be opened", path.string());
    const auto require = [&](const char* key) {
        cv::FileNode node = fs[key];
        if (node.empty()) fail("camera file '{}': missing entry '{}'", path.string(), key);
        return node;
    };
    CameraModel camera;
    camera.image_size = {static_cast<int>(require("image_width")), static_cast<int>(require("image_height"))};
    cv::Mat matrix, distortion;
    require("camera_matrix") >> matrix;
    require("distortion_coefficients") >> distortion;
    if (matrix.rows != 3 || matrix.cols != 3)
        fail("camera file '{}': camera_matrix must be 3x3, got {}x{}", path.string(), matrix.rows, matrix.cols);
    matrix.convertTo(matrix, CV_64F);
    camera.matrix = cv::Matx33d(matrix);
    distortion.convertTo(distortion, CV_64F);
    camera.distortion.assign(distortion.begin<double>(), distortion.end<double>());
    if (camera.distortion.size() != 4 && camera.distortion.size() != 5 && camera.distortion.size() != 8)
        fail("camera file '{}': distortion_coefficients must have 4, 5 or 8 entries, got {}", path.string(),
             camera.distortion.size());
    if (!fs["rms_reprojection_error"].empty()) camera.rms_reprojection_error = fs["rms_reprojection_error"];
    if (!fs["views"].empty()) camera.views = fs["views"];
    if (!fs["intrinsics_std_dev"].empty()) {
        cv::Mat std_dev;
        fs["intrinsics_std_dev"] >> std_dev;
        std_dev.convertTo(std_dev, CV_64F);
        camera.intrinsics_std_dev.assign(std_dev.begin<double>(), std_dev.end<double>());
        if (camera.intrinsics_std_dev.size() != 4 + camera.distortion.size())
            fail("camera file '{}': intrinsics_std_dev must have {} entries (fx fy cx cy and the distortion), got {}",
                 path.string(), 4 + camera.distortion.size(), camera.intrinsics_std_dev.size());
    }
    if (camera.image_size.width <= 0 || camera.image_size.height <= 0)
        fail("camera file '{}': image size {}x{} is not positive", path.string(), camera.image_size.width,
             camera.image_size.height);
    if (!(camera.fx() > 0.0) || !(camera.fy() > 0.0) || !std::isfinite(camera.cx()) || !std::isfinite(camera.cy()))
        fail("camera file '{}': camera_matrix has non-positive focal lengths", path.string());
    return camera;
}

void require_image_size(const CameraModel& camera, cv::Size size, const std::string& what) {
    if (size != camera.image_size)
        fail("{} is {}x{} pixels but the camera was calibrated at {}x{}", what, size.width, size.height,
             camera.image_size.width, camera.image_size.height);
}

}  // namespace surfscatter::photo
