#include "surfscatter/photo/camera_model.hpp"

#include <cmath>
#include <exception>
#include <limits>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/photo/file_storage.hpp"

namespace surfscatter::photo {

void write_camera(const std::filesystem::path& path, const CameraModel& camera) {
    cv::FileStorage fs;
    try {
        // Built in memory (the format from the extension), written atomically (core/output_files.hpp).
        fs.open(path.string(), cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
    } catch (const cv::Exception& e) {
        fail("camera file '{}' could not be written: {}", path.string(), e.what());
    }
    if (!fs.isOpened()) fail("camera file '{}' could not be written", path.string());
    if (!camera.image_size.empty()) {  // unknown (read from a file without it): still taken from the photograph
        fs << "image_width" << camera.image_size.width;
        fs << "image_height" << camera.image_size.height;
    }
    fs << "camera_matrix" << cv::Mat(camera.matrix);
    fs << "distortion_coefficients" << cv::Mat(camera.distortion).reshape(1, 1);
    fs << "rms_reprojection_error" << camera.rms_reprojection_error;
    fs << "views" << camera.views;
    if (!camera.intrinsics_std_dev.empty()) fs << "intrinsics_std_dev" << cv::Mat(camera.intrinsics_std_dev).reshape(1, 1);
    if (!camera.calibration_warnings.empty()) {
        fs << "calibration_warnings" << "[";
        for (const auto& w : camera.calibration_warnings) fs << w;
        fs << "]";
    }
    write_file_atomically(path, fs.releaseAndGetString());
}

namespace {
// Largest image side a camera file may declare (a guard against absurd sizes before any image is allocated).
constexpr int kMaxImageSide = 100000;

class CameraFileReader {
public:
    CameraFileReader(const cv::FileStorage& fs, std::string name) : fs_(fs), name_(std::move(name)) {}

    cv::FileNode node(const char* key) const {
        cv::FileNode n = fs_[key];
        if (n.empty()) fail("camera file '{}': missing entry '{}'", name_, key);
        return n;
    }
    int integer(const char* key, int low, int high) const {
        const cv::FileNode n = node(key);
        if (!n.isInt()) fail("camera file '{}': '{}' must be an integer", name_, key);
        const int value = static_cast<int>(n);
        if (value < low || value > high)
            fail("camera file '{}': {} = {} is outside [{}, {}]", name_, key, value, low, high);
        return value;
    }
    double number(const char* key) const {
        const cv::FileNode n = node(key);
        if (!n.isReal() && !n.isInt()) fail("camera file '{}': '{}' must be a number", name_, key);
        const double value = static_cast<double>(n);
        if (!std::isfinite(value)) fail("camera file '{}': {} = {} is not finite", name_, key, value);
        return value;
    }
    // An !!opencv-matrix of finite numbers, as doubles.
    cv::Mat matrix(const char* key) const {
        const cv::FileNode n = node(key);
        cv::Mat m;
        // OpenCV allocates rows x cols before it reads the data: a camera file's matrices are small (3 x 3, at most
        // 18 coefficients), so refuse a header of 10^5 x 10^5 before it becomes a 40 GB allocation (fuzz_camera_file).
        constexpr int kMaxEntries = 64;
        if (n.isMap() && n["rows"].isInt() && n["cols"].isInt()) {
            const auto rows = static_cast<long long>(static_cast<int>(n["rows"])),
                       cols = static_cast<long long>(static_cast<int>(n["cols"]));
            if (rows < 0 || cols < 0 || rows * cols > kMaxEntries)
                fail("camera file '{}': '{}' is {} x {}, larger than any camera matrix or coefficient list ({} entries)",
                     name_, key, rows, cols, kMaxEntries);
            try {
                n >> m;
            } catch (const cv::Exception&) {
                m.release();
            }
        }
        // Without integer rows and cols it is no OpenCV matrix (and OpenCV would size it from garbage).
        if (m.empty() || m.channels() != 1)
            fail("camera file '{}': '{}' must be an OpenCV matrix (!!opencv-matrix with rows, cols, dt, data)", name_,
                 key);
        m.convertTo(m, CV_64F);
        for (int r = 0; r < m.rows; ++r)
            for (int c = 0; c < m.cols; ++c)
                if (!std::isfinite(m.at<double>(r, c)))
                    fail("camera file '{}': {} entry ({}, {}) is {}, not a finite number", name_, key, r, c,
                         m.at<double>(r, c));
        return m;
    }
    std::vector<double> vector(const char* key) const {
        const cv::Mat m = matrix(key);
        if (m.rows != 1 && m.cols != 1)
            fail("camera file '{}': '{}' must be one row or column, got {}x{}", name_, key, m.rows, m.cols);
        return {m.begin<double>(), m.end<double>()};
    }
    const std::string& name() const { return name_; }

private:
    const cv::FileStorage& fs_;
    std::string name_;
};

CameraModel parse_camera(const cv::FileStorage& fs, const std::string& name) {
    const CameraFileReader in(fs, name);
    CameraModel camera;
    // OpenCV's own files may hold the intrinsics alone; the photograph then gives the size (camera_for_image).
    if (!fs["image_width"].empty() || !fs["image_height"].empty())
        camera.image_size = {in.integer("image_width", 1, kMaxImageSide), in.integer("image_height", 1, kMaxImageSide)};
    const cv::Mat matrix = in.matrix("camera_matrix");
    if (matrix.rows != 3 || matrix.cols != 3)
        fail("camera file '{}': camera_matrix must be 3x3, got {}x{}", name, matrix.rows, matrix.cols);
    camera.matrix = cv::Matx33d(matrix);
    const auto& k = camera.matrix;
    if (!(k(0, 0) > 0.0) || !(k(1, 1) > 0.0))
        fail("camera file '{}': camera_matrix focal lengths fx = {}, fy = {} must be positive", name, k(0, 0), k(1, 1));
    if (k(1, 0) != 0.0 || k(2, 0) != 0.0 || k(2, 1) != 0.0 || k(2, 2) != 1.0)
        fail("camera file '{}': camera_matrix must be [fx s cx; 0 fy cy; 0 0 1], got last rows [{} {} {}; {} {} {}]",
             name, k(1, 0), k(1, 1), k(1, 2), k(2, 0), k(2, 1), k(2, 2));
    camera.distortion = in.vector("distortion_coefficients");
    if (camera.distortion.size() != 4 && camera.distortion.size() != 5 && camera.distortion.size() != 8)
        fail("camera file '{}': distortion_coefficients must have 4, 5 or 8 entries, got {}", name,
             camera.distortion.size());
    if (!fs["rms_reprojection_error"].empty()) camera.rms_reprojection_error = in.number("rms_reprojection_error");
    if (!fs["views"].empty()) camera.views = in.integer("views", 0, std::numeric_limits<int>::max());
    if (!fs["intrinsics_std_dev"].empty()) {
        camera.intrinsics_std_dev = in.vector("intrinsics_std_dev");
        if (camera.intrinsics_std_dev.size() != 4 + camera.distortion.size())
            fail("camera file '{}': intrinsics_std_dev must have {} entries (fx fy cx cy and the distortion), got {}",
                 name, 4 + camera.distortion.size(), camera.intrinsics_std_dev.size());
    }
    if (const cv::FileNode warnings = fs["calibration_warnings"]; !warnings.empty()) {
        if (!warnings.isSeq()) fail("camera file '{}': calibration_warnings must be a list of strings", name);
        for (const auto& w : warnings) {
            if (!w.isString()) fail("camera file '{}': calibration_warnings must be a list of strings", name);
            camera.calibration_warnings.push_back(static_cast<std::string>(w));
        }
    }
    return camera;
}
}  // namespace

CameraModel read_camera(const std::filesystem::path& path) {
    const std::string name = path.string();
    cv::FileStorage fs;
    open_for_reading(fs, name, "camera file");
    try {
        return parse_camera(fs, name);
    } catch (const cv::Exception& e) {
        fail("camera file '{}' could not be read: {}", name, e.err);
    }
}

void require_image_size(const CameraModel& camera, cv::Size size, const std::string& what) {
    if (!camera.image_size.empty() && size != camera.image_size)
        fail("{} is {}x{} pixels but the camera was calibrated at {}x{}", what, size.width, size.height,
             camera.image_size.width, camera.image_size.height);
}

CameraModel camera_for_image(const CameraModel& camera, cv::Size size, const std::string& what) {
    require_image_size(camera, size, what);
    CameraModel sized = camera;
    sized.image_size = size;
    return sized;
}

}  // namespace surfscatter::photo
