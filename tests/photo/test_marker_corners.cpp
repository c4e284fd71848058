#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "surfscatter/photo/marker_corners.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {
namespace {

constexpr double kMarkerLength = 0.05;
constexpr int kCells = 6;  // 4x4 bits and the border

struct Scene {
    CameraModel camera = synthetic::true_camera();
    cv::Mat linear;                      // CV_32FC1 linear light
    std::vector<cv::Point2f> truth;      // the marker's corners projected through the lens
};

// A 50 mm marker 30 cm away at about 35 degrees, defocused by `blur` px (in light), written as 8-bit sRGB and
// read back, with `noise` (fraction of white, linear light) added before encoding.
Scene photograph(double blur, double noise) {
    Scene s;
    static const cv::Mat rays = synthetic::sub_pixel_rays(s.camera);
    const auto texture = synthetic::marker_texture(4, kMarkerLength);
    const auto pose = synthetic::look_at({0.05, -0.17, 0.25}, {0.0, 0.0, 0.0}, {0, 1, 0});
    cv::Mat light = synthetic::render_plane_linear(texture.image, texture.size, texture.size, s.camera, rays, pose, 90);
    if (blur > 0) cv::GaussianBlur(light, light, cv::Size(), blur);
    if (noise > 0) {
        cv::Mat n(light.size(), CV_32FC1);
        cv::RNG rng(99);
        rng.fill(n, cv::RNG::NORMAL, 0.0, noise);
        light += n;
    }
    s.linear = to_linear_gray(synthetic::linear_rgb_from_srgb8(synthetic::srgb8_from_linear(light)));
    const double h = 0.5 * kMarkerLength;
    const std::vector<cv::Point3d> object{{-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}};
    std::vector<cv::Point2d> projected;
    cv::projectPoints(object, pose.rvec, pose.tvec, s.camera.matrix, s.camera.distortion, projected);
    for (const auto& p : projected) s.truth.emplace_back(p);
    return s;
}

// The detector's corners (OpenCV's cornerSubPix on the display encoding), as the pose used them before.
std::vector<cv::Point2f> detected_corners(const cv::Mat& linear_gray) {
    cv::Mat rgb;
    cv::cvtColor(linear_gray, rgb, cv::COLOR_GRAY2RGB);
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(to_gray8(rgb), dictionary_by_name("4X4_50"), corners, ids, marker_detector_parameters());
    EXPECT_EQ(ids.size(), 1u);
    return corners.empty() ? std::vector<cv::Point2f>{} : corners.front();
}

double max_error(const std::vector<cv::Point2f>& a, const std::vector<cv::Point2f>& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, double(cv::norm(a[i] - b[i])));
    return worst;
}

struct Case {
    double blur, noise, tolerance;
};
class MarkerCorners : public ::testing::TestWithParam<Case> {};

TEST_P(MarkerCorners, EdgesInLinearLightGiveTheCornersWhereCornerSubPixIsBiased) {
    const Case c = GetParam();
    const Scene s = photograph(c.blur, c.noise);
    const auto detected = detected_corners(s.linear);
    ASSERT_EQ(detected.size(), 4u);
    const auto refined = refine_marker_corners(s.linear, detected, s.camera, kCells);
    ASSERT_TRUE(refined.has_value());
    const double detector = max_error(detected, s.truth), edges = max_error(*refined, s.truth);
    std::printf("[ measured ] blur %.1f px, noise %.0f %%: corner error detector %.3f px, edges %.3f px\n", c.blur,
                100 * c.noise, detector, edges);
    EXPECT_LT(edges, c.tolerance);
    EXPECT_LT(edges, detector);
}

INSTANTIATE_TEST_SUITE_P(BlurAndNoise, MarkerCorners,
                         ::testing::Values(Case{0.0, 0.0, 0.03}, Case{1.0, 0.0, 0.03}, Case{2.0, 0.0, 0.05},
                                           Case{1.0, 0.02, 0.1}, Case{1.0, 0.05, 0.2}));

TEST(MarkerCornersLimits, TooSmallOrCutMarkersAreLeftToTheDetector) {
    const Scene s = photograph(0.0, 0.0);
    const auto detected = detected_corners(s.linear);
    ASSERT_EQ(detected.size(), 4u);
    // 3 px per cell: too small to hold a profile.
    std::vector<cv::Point2f> tiny{{100, 100}, {118, 100}, {118, 118}, {100, 118}};
    EXPECT_FALSE(refine_marker_corners(s.linear, tiny, s.camera, kCells).has_value());
    // The marker cut by the image border: a crop that keeps only its left part.
    const cv::Rect left(0, 0, static_cast<int>(0.5 * (detected[0].x + detected[1].x)), s.linear.rows);
    EXPECT_FALSE(refine_marker_corners(s.linear(left).clone(), detected, s.camera, kCells).has_value());
    // Corners that are not on the marker's edges (a flat grey image) give no edges.
    const cv::Mat flat(s.linear.size(), CV_32FC1, cv::Scalar(0.3));
    EXPECT_FALSE(refine_marker_corners(flat, detected, s.camera, kCells).has_value());
}

}  // namespace
}  // namespace surfscatter::photo
