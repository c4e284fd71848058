#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/pose.hpp"

namespace surfscatter::photo {
namespace {

// A realistic set-up: 1280x960 camera, 50 degree horizontal field of view, mild barrel distortion, a 60 mm marker
// about 40 cm away.
CameraModel test_camera(bool distorted) {
    CameraModel c;
    c.image_size = {1280, 960};
    c.matrix = cv::Matx33d(1370.0, 0.0, 645.3, 0.0, 1372.0, 478.6, 0.0, 0.0, 1.0);
    c.distortion = distorted ? std::vector<double>{-0.12, 0.05, 0.0008, -0.0005, 0.0} : std::vector<double>(5, 0.0);
    return c;
}

constexpr double kMarkerLength = 0.06;

double rotation_error_degrees(const cv::Matx33d& a, const cv::Matx33d& b) {
    const cv::Matx33d d = a.t() * b;
    const double c = std::clamp(0.5 * (cv::trace(d) - 1.0), -1.0, 1.0);
    return std::acos(c) * 180.0 / M_PI;
}

struct PoseCase {
    cv::Vec3d eye;
    cv::Vec3d up;
    double blur_sigma;  // pixels, 0 = none
    double noise_sigma; // 8-bit code values
};

class MarkerPoseRecovery : public ::testing::TestWithParam<PoseCase> {};

TEST_P(MarkerPoseRecovery, CameraPositionWithin2mmAndRotationWithinHalfDegree) {
    const PoseCase& pc = GetParam();
    const CameraModel camera = test_camera(true);
    static const cv::Mat rays = synthetic::sub_pixel_rays(camera);
    const auto texture = synthetic::marker_texture(7, kMarkerLength);
    const auto truth = synthetic::look_at(pc.eye, {0.01, -0.005, 0.0}, pc.up);
    // Defocus blurs the light (linear); the camera then writes sRGB code values, with sensor noise.
    cv::Mat linear = synthetic::render_plane_linear(texture.image, texture.size, texture.size, camera, rays, truth, 160.0);
    if (pc.blur_sigma > 0.0) cv::GaussianBlur(linear, linear, cv::Size(), pc.blur_sigma);
    cv::Mat image = synthetic::srgb8_from_linear(linear);
    if (pc.noise_sigma > 0.0) {
        cv::Mat noise(image.size(), CV_32F);
        cv::RNG rng(1234);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, pc.noise_sigma);
        cv::Mat f;
        image.convertTo(f, CV_32F);
        f += noise;
        f.convertTo(image, CV_8U);
    }

    MarkerPoseOptions options;
    options.marker_length = kMarkerLength;
    const MarkerPose pose = estimate_marker_pose(synthetic::linear_rgb_from_srgb8(image), camera, options);
    EXPECT_EQ(pose.marker_id, 7);
    EXPECT_EQ(pose.corners.method, "pattern");
    EXPECT_FALSE(pose.pose.ambiguous);
    EXPECT_LT(pose.pose.best.reprojection_rms, 0.5);
    // The issue asks for 2 mm and 0.5 degree; the pattern-fitted corners give about a hundredth of that.
    EXPECT_LT(cv::norm(pose.pose.best.position - pc.eye), 0.0002) << pose.pose.best.position << " vs " << pc.eye;
    cv::Matx33d r_true, r_est;
    cv::Rodrigues(truth.rvec, r_true);
    cv::Rodrigues(pose.pose.best.rvec, r_est);
    const double rotation_error = rotation_error_degrees(r_true, r_est);
    EXPECT_LT(rotation_error, 0.02);
    std::printf("[ measured ] position error %.4f mm, rotation error %.4f deg, reprojection %.3f px\n",
                1e3 * cv::norm(pose.pose.best.position - pc.eye), rotation_error, pose.pose.best.reprojection_rms);
}

INSTANTIATE_TEST_SUITE_P(
    Views, MarkerPoseRecovery,
    ::testing::Values(PoseCase{{0.0, -0.25, 0.32}, {0, 1, 0}, 0.0, 0.0},      // 38 degrees from the normal
                      PoseCase{{0.15, 0.1, 0.35}, {0, 1, 0}, 0.0, 0.0},       // off to the side
                      PoseCase{{-0.2, -0.2, 0.25}, {1, 1, 0}, 0.0, 0.0},      // rolled 45 degrees
                      PoseCase{{0.05, 0.3, 0.2}, {0, -1, 0}, 0.0, 0.0},       // upside down, grazing
                      PoseCase{{0.0, -0.25, 0.32}, {0, 1, 0}, 1.5, 0.0},      // defocus blur
                      PoseCase{{0.1, -0.2, 0.3}, {0, 1, 0}, 0.8, 4.0}));      // blur and sensor noise

TEST(MarkerPose, SensorReprojectsTheMarkerCentreWhereTheCameraSeesIt) {
    CameraModel camera = test_camera(false);
    const cv::Vec3d eye{0.1, -0.2, 0.3};
    const MitsubaSensor s =
        mitsuba_sensor(camera, synthetic::camera_to_world(synthetic::look_at(eye, {0, 0, 0}, {0, 1, 0})), 0.5);
    EXPECT_NEAR(s.fov_x_deg, 2.0 * std::atan(640.0 / 1370.0) * 180.0 / M_PI, 1e-9);
    // Optical axis at cx + 0.5 = 645.8 of 1280 -> ppo_x = 0.5 - 645.8/1280.
    EXPECT_NEAR(s.principal_point_offset_x, 0.5 - 645.8 / 1280.0, 1e-12);
    EXPECT_NEAR(s.principal_point_offset_y, 0.5 - 479.1 / 960.0, 1e-12);
    // Mitsuba camera axes: x left, y up, z forward, all unit and right-handed.
    const cv::Vec3d x(s.to_world(0, 0), s.to_world(1, 0), s.to_world(2, 0));
    const cv::Vec3d y(s.to_world(0, 1), s.to_world(1, 1), s.to_world(2, 1));
    const cv::Vec3d z(s.to_world(0, 2), s.to_world(1, 2), s.to_world(2, 2));
    EXPECT_NEAR(cv::norm(x.cross(y) - z), 0.0, 1e-12);
    EXPECT_NEAR(cv::norm(z - cv::normalize(-eye)), 0.0, 1e-12);  // looks at the origin
    EXPECT_GT(y[2], 0.0);  // image up points away from the floor here
    EXPECT_NEAR(cv::norm(s.origin - eye), 0.0, 1e-12);
    EXPECT_NEAR(cv::norm(s.target - (eye + 0.5 * z)), 0.0, 1e-12);
    EXPECT_NE(s.xml.find("<lookat origin=\"0.1, -0.2, 0.3\""), std::string::npos) << s.xml;
    EXPECT_NE(s.xml.find("<integer name=\"width\" value=\"1280\"/>"), std::string::npos);
}

TEST(MarkerPose, NoMarkerGivesAClearError) {
    const cv::Mat blank(480, 640, CV_8UC1, cv::Scalar(128));
    MarkerPoseOptions options;
    options.marker_length = kMarkerLength;
    CameraModel camera = test_camera(false);
    camera.image_size = {640, 480};
    try {
        estimate_marker_pose(synthetic::linear_rgb_from_srgb8(blank), camera, options);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("no ArUco marker"), std::string::npos);
    }
}

TEST(MarkerPose, WrongIdAndUnknownDictionaryAreReported) {
    const CameraModel camera = test_camera(false);
    static const cv::Mat rays = synthetic::sub_pixel_rays(camera);
    const auto texture = synthetic::marker_texture(3, kMarkerLength);
    const auto truth = synthetic::look_at({0.0, -0.1, 0.3}, {0, 0, 0}, {0, 1, 0});
    const cv::Mat image = synthetic::linear_rgb_from_srgb8(
        synthetic::render_plane(texture.image, texture.size, texture.size, camera, rays, truth, 128));
    MarkerPoseOptions options;
    options.marker_length = kMarkerLength;
    options.marker_id = 5;
    EXPECT_THROW(estimate_marker_pose(image, camera, options), Error);
    options.marker_id = 3;
    EXPECT_NO_THROW(estimate_marker_pose(image, camera, options));
    options.dictionary = "9X9_7";
    EXPECT_THROW(estimate_marker_pose(image, camera, options), Error);
}

}  // namespace
}  // namespace surfscatter::photo
