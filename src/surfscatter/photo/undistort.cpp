#include "surfscatter/photo/undistort.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace surfscatter::photo {

cv::Mat undistort_image(const cv::Mat& image, const CameraModel& camera) {
    require_image_size(camera, image.size(), "the photograph");
    cv::Mat map_x, map_y, out;
    cv::initUndistortRectifyMap(camera.matrix, camera.distortion, cv::noArray(), camera.matrix, image.size(),
                                CV_32FC1, map_x, map_y);
    cv::remap(image, out, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0));
    return out;
}

}  // namespace surfscatter::photo
