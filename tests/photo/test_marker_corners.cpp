#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
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
    cv::aruco::detectMarkers(to_gray8(rgb), load_dictionary("4X4_50"), corners, ids, marker_detector_parameters());
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
class MarkerEdgeFit : public ::testing::TestWithParam<Case> {};

TEST_P(MarkerEdgeFit, EdgesInLinearLightGiveTheCornersWhereCornerSubPixIsBiased) {
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

INSTANTIATE_TEST_SUITE_P(BlurAndNoise, MarkerEdgeFit,
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


// ---- refine_marker: the candidates and the pattern fit.

// A 6x6 marker (8 cells a side) of `size` px, written as a camera would: optical blur (`blur` px) in light, sRGB
// encoding, then `sharpen` (unsharp mask in the encoded domain, as camera processing does) and JPEG at `quality`.
struct ProcessedShot {
    CameraModel camera;
    cv::Mat linear_gray;
    std::vector<cv::Point2f> truth, detected;
    cv::Mat cells;
};
ProcessedShot processed_shot(double size, double tilt_deg, int seed, double blur, double sharpen, int quality) {
    ProcessedShot s;
    s.camera.image_size = {640, 480};
    s.camera.matrix = cv::Matx33d(628.0, 0.0, 324.1, 0.0, 628.2, 260.9, 0.0, 0.0, 1.0);
    s.camera.distortion = {0.0995, -0.206, 0.0075, 0.0034, 0.0};
    static const cv::Mat rays = synthetic::sub_pixel_rays(s.camera);
    constexpr double kLength = 0.04;
    const auto texture = synthetic::marker_texture(7, kLength, "6X6_250");
    const double distance = s.camera.fx() * kLength / size, t = tilt_deg * M_PI / 180;
    const cv::Vec3d eye(distance * std::sin(t) * std::cos(seed), distance * std::sin(t) * std::sin(seed),
                        distance * std::cos(t));
    const auto pose = synthetic::look_at(eye, {0.002 * seed, -0.001 * seed, 0.0}, {0.2, 1, 0.1});
    cv::Mat light = synthetic::render_plane_linear(texture.image, texture.size, texture.size, s.camera, rays, pose, 150);
    cv::GaussianBlur(light, light, cv::Size(), blur);
    cv::Mat encoded;
    synthetic::srgb8_from_linear(light).convertTo(encoded, CV_32F);
    if (sharpen > 0) {
        cv::Mat blurred;
        cv::GaussianBlur(encoded, blurred, cv::Size(), 1.0);
        encoded += sharpen * (encoded - blurred);
    }
    cv::Mat photo8;
    encoded.convertTo(photo8, CV_8U);
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", photo8, jpeg, {cv::IMWRITE_JPEG_QUALITY, quality});
    const cv::Mat rgb = synthetic::linear_rgb_from_srgb8(cv::imdecode(jpeg, cv::IMREAD_GRAYSCALE));
    s.linear_gray = to_linear_gray(rgb);
    const auto dictionary = load_dictionary("6X6_250");
    const DetectedMarkers found = detect_markers(rgb, dictionary);
    if (found.ids.size() == 1) s.detected = found.corners[0];
    s.cells = marker_cells(*dictionary, 7);
    const double h = 0.5 * kLength;
    std::vector<cv::Point2d> projected;
    cv::projectPoints(std::vector<cv::Point3d>{{-h, h, 0}, {h, h, 0}, {h, -h, 0}, {-h, -h, 0}}, pose.rvec, pose.tvec,
                      s.camera.matrix, s.camera.distortion, projected);
    for (const auto& p : projected) s.truth.emplace_back(p);
    return s;
}

// Mean displacement of corners away from the marker's centre (negative: inside the marker).
double mean_outward(const std::vector<cv::Point2f>& corners, const std::vector<cv::Point2f>& truth) {
    const cv::Point2f centre = 0.25f * (truth[0] + truth[1] + truth[2] + truth[3]);
    double sum = 0;
    for (std::size_t k = 0; k < 4; ++k) {
        const cv::Point2f radial = truth[k] - centre;
        sum += (corners[k] - truth[k]).dot(radial) / cv::norm(radial) / 4;
    }
    return sum;
}

// The camera processing real JPEGs carry (sharpening in the encoded domain, compression) must not bias the
// refined corners, while the detector's contour corners sit inside the marker: this is why refined corners on the
// tutorial photographs lie outside OpenCV's figures (test_real_photos.cpp).
TEST(MarkerCornersOnProcessedJpegs, PatternFitIsUnbiasedWhereTheDetectorSitsInside) {
    for (const double sharpen : {0.0, 1.5})
        for (const int quality : {95, 75}) {
            double refined_outward = 0, detector_outward = 0, worst = 0;
            int shots = 0;
            for (int seed = 0; seed < 4; ++seed) {
                const ProcessedShot s = processed_shot(40, 35, seed, 0.8, sharpen, quality);
                ASSERT_EQ(s.detected.size(), 4u);
                const MarkerCorners refined = refine_marker(s.linear_gray, s.detected, s.camera, s.cells);
                EXPECT_EQ(refined.method, "pattern");
                refined_outward += mean_outward(refined.corners, s.truth);
                detector_outward += mean_outward(s.detected, s.truth);
                worst = std::max(worst, max_error(refined.corners, s.truth));
                ++shots;
            }
            refined_outward /= shots, detector_outward /= shots;
            std::printf("[ measured ] 40 px marker, sharpening %.1f, JPEG quality %d: refined corners %.3f px outward "
                        "(worst error %.3f px), detector's %.3f px\n",
                        sharpen, quality, refined_outward, worst, detector_outward);
            EXPECT_LT(std::abs(refined_outward), 0.15);
            EXPECT_LT(worst, 0.3);
            EXPECT_LT(detector_outward, -0.5);
        }
}

// Never worse than the detector, from 2 to 25 px per cell; no cornerSubPix window wider than a cell.
TEST(MarkerCornersCandidates, NeverWorseThanTheDetectorAndNoWindowWiderThanACell) {
    for (const double size : {18.0, 30.0, 40.0, 80.0, 200.0}) {
        const ProcessedShot s = processed_shot(size, 10, 2, 0.5, 0.0, 95);
        ASSERT_EQ(s.detected.size(), 4u) << size;
        const MarkerCorners refined = refine_marker(s.linear_gray, s.detected, s.camera, s.cells);
        const double cell = size / s.cells.rows;
        const bool has_subpix = std::any_of(refined.candidates.begin(), refined.candidates.end(),
                                            [](const CornerCandidate& c) { return c.method == "cornerSubPix"; });
        EXPECT_EQ(has_subpix, cell >= 3.0) << size;  // its smallest window is 3 px wide
        EXPECT_EQ(refined.candidates.front().method, "detector");
        for (const auto& c : refined.candidates) {
            if (c.method == "pattern") continue;
            EXPECT_TRUE(c.pattern_residual.has_value()) << c.method;
        }
        const double detector = max_error(s.detected, s.truth), chosen = max_error(refined.corners, s.truth);
        std::printf("[ measured ] %.0f px marker (%.1f px per cell): %s corners %.3f px, detector %.3f px\n", size,
                    cell, refined.method.c_str(), chosen, detector);
        EXPECT_LE(chosen, detector);
    }
}

}  // namespace
}  // namespace surfscatter::photo
