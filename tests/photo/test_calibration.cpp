#include <cstdio>

#include <filesystem>
#include <tuple>

#include <unistd.h>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/calibration.hpp"

namespace surfscatter::photo {
namespace {

const cv::Mat& rays() {
    static const cv::Mat r = synthetic::sub_pixel_rays(synthetic::true_camera());
    return r;
}

// The board as an 8-bit sRGB photograph read back to linear light, as `surfscatter calibrate` reads a PNG.
cv::Mat photograph(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                   const synthetic::Extrinsics& view) {
    return synthetic::linear_rgb_from_srgb8(synthetic::render_plane(texture, width, height, camera, rays(), view, 150));
}

// Camera positions around a board at the origin: varied tilt, roll and distance so that the views fill the frame.
std::vector<synthetic::Extrinsics> views() {
    const std::vector<std::pair<cv::Vec3d, cv::Vec3d>> eyes_ups{
        {{0.0, -0.05, 0.33}, {0, 1, 0}},    {{0.16, 0.0, 0.30}, {0, 1, 0}},     {{-0.16, 0.02, 0.30}, {0, 1, 0}},
        {{0.0, 0.17, 0.28}, {0.3, 1, 0}},   {{0.0, -0.17, 0.28}, {-0.3, 1, 0}}, {{0.12, 0.12, 0.29}, {1, 1, 0}},
        {{-0.12, -0.1, 0.3}, {1, -1, 0}},   {{0.05, 0.0, 0.26}, {1, 0, 0}},     {{-0.2, 0.1, 0.25}, {0, 1, 0}},
        {{0.2, -0.1, 0.27}, {0.2, 1, 0}}};
    std::vector<synthetic::Extrinsics> out;
    for (const auto& [eye, up] : eyes_ups) out.push_back(synthetic::look_at(eye, {0.0, 0.0, 0.0}, up));
    // Four close views with the board pushed into the image corners, where distortion is largest.
    for (const cv::Vec3d& target : {cv::Vec3d{0.07, 0.05, 0}, {-0.07, 0.05, 0}, {0.07, -0.05, 0}, {-0.07, -0.05, 0}})
        out.push_back(synthetic::look_at(cv::Vec3d{0.0, 0.0, 0.22} + 0.3 * target, target, {0, 1, 0}));
    return out;
}

// Largest difference, in pixels, between the distortion displacements of the two models (principal point and focal
// length taken out: both evaluated on the same normalised rays) within the true image less a border of `inset` px.
double max_distortion_difference_px(const CameraModel& truth, const CameraModel& estimate, int inset) {
    std::vector<cv::Point3d> rays;
    for (int y = inset; y <= truth.image_size.height - inset; y += 20)
        for (int x = inset; x <= truth.image_size.width - inset; x += 20) {
            std::vector<cv::Point2d> pixel{{double(x), double(y)}}, normalised;
            cv::undistortPoints(pixel, normalised, truth.matrix, truth.distortion, cv::noArray(), cv::noArray(),
                                cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-10));
            rays.emplace_back(normalised[0].x, normalised[0].y, 1.0);
        }
    const cv::Matx33d k(truth.fx(), 0, 0, 0, truth.fy(), 0, 0, 0, 1);
    std::vector<cv::Point2d> a, b;
    cv::projectPoints(rays, cv::Vec3d(), cv::Vec3d(), k, truth.distortion, a);
    cv::projectPoints(rays, cv::Vec3d(), cv::Vec3d(), k, estimate.distortion, b);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, cv::norm(a[i] - b[i]));
    return worst;
}

// Distortion is compared over the image less a border of `inset` pixels: a chessboard must be seen whole, so its
// views never reach the image corners and the fit extrapolates there.
void expect_recovers(const CameraModel& truth, const CalibrationResult& result, const char* what, int inset,
                     double max_distortion_error_px) {
    const CameraModel& c = result.camera;
    const double distortion_error = max_distortion_difference_px(truth, c, inset);
    ASSERT_EQ(c.intrinsics_std_dev.size(), 4 + c.distortion.size());
    const auto& sd = c.intrinsics_std_dev;
    std::printf("[ measured ] %s: fx %.2f +- %.2f fy %.2f +- %.2f cx %.2f +- %.2f cy %.2f +- %.2f (true 1010 1006 "
                "487.5 352.2), k1 %.4f k2 %.4f, RMS %.3f px, max distortion difference %.3f px (border %d px left "
                "out), %zu views\n",
                what, c.fx(), sd[0], c.fy(), sd[1], c.cx(), sd[2], c.cy(), sd[3], c.distortion[0], c.distortion[1],
                c.rms_reprojection_error, distortion_error, inset, result.used.size());
    // The truth within 3 of the calibration's own standard deviations: the error is noise, not bias.
    for (const auto& [estimate, true_value, k] : {std::tuple{c.fx(), truth.fx(), 0}, {c.fy(), truth.fy(), 1},
                                                  {c.cx(), truth.cx(), 2}, {c.cy(), truth.cy(), 3}})
        EXPECT_LT(std::abs(estimate - true_value), 3 * sd[static_cast<std::size_t>(k)]) << what << " parameter " << k;
    EXPECT_NEAR(c.fx(), truth.fx(), 0.003 * truth.fx());
    EXPECT_NEAR(c.fy(), truth.fy(), 0.003 * truth.fy());
    EXPECT_NEAR(c.cx(), truth.cx(), 2.0);
    EXPECT_NEAR(c.cy(), truth.cy(), 2.0);
    EXPECT_LT(c.rms_reprojection_error, 0.15);
    EXPECT_LT(distortion_error, max_distortion_error_px);
    EXPECT_EQ(c.image_size, truth.image_size);
}

TEST(Calibration, CharucoRecoversKnownIntrinsicsAndDistortionDespiteOcclusion) {
    const CameraModel truth = synthetic::true_camera();
    const auto board = synthetic::charuco_texture(10, 7, 0.03, 0.022);
    std::vector<CalibrationInput> inputs;
    int index = 0;
    for (const auto& view : views()) {
        cv::Mat image = photograph(board.image, board.width, board.height, truth, view);
        if (index == 3) image(cv::Rect(0, 0, 480, 360)).setTo(cv::Scalar::all(0.1));  // a hand over a quarter of the board
        if (index == 5) cv::GaussianBlur(image, image, cv::Size(), 1.2);
        inputs.push_back({"view" + std::to_string(index++) + ".png", image});
    }
    inputs.push_back({"empty.png", cv::Mat(720, 960, CV_32FC3, cv::Scalar::all(0.2))});
    BoardSpec spec;
    spec.type = BoardType::Charuco;
    spec.squares_x = 10, spec.squares_y = 7, spec.square_length = 0.03, spec.marker_length = 0.022;
    const CalibrationResult result = calibrate_camera(inputs, spec);
    EXPECT_TRUE(result.camera.calibration_warnings.empty()) << result.camera.calibration_warnings.front();
    ASSERT_EQ(result.rejected, std::vector<std::string>{"empty.png"});
    expect_recovers(truth, result, "ChArUco", 0, 0.5);
}

TEST(Calibration, ChessboardRecoversKnownIntrinsics) {
    const CameraModel truth = synthetic::true_camera();
    const auto board = synthetic::chessboard_texture(8, 6, 0.025);
    std::vector<CalibrationInput> inputs;
    int index = 0;
    for (const auto& view : views()) {
        inputs.push_back({"chess" + std::to_string(index++) + ".png",
                          photograph(board.image, board.width, board.height, truth, view)});
    }
    BoardSpec spec;
    spec.type = BoardType::Chessboard;
    spec.squares_x = 8, spec.squares_y = 6, spec.square_length = 0.025;
    const CalibrationResult result = calibrate_camera(inputs, spec);
    EXPECT_TRUE(result.camera.calibration_warnings.empty()) << result.camera.calibration_warnings.front();
    EXPECT_EQ(result.rejected.size(), 4u);  // the four views with the board cut by the image border
    expect_recovers(truth, result, "chessboard", 120, 1.0);
}

TEST(Calibration, TooFewViewsNamesTheRejectedImages) {
    const CameraModel truth = synthetic::true_camera();
    const auto board = synthetic::charuco_texture(10, 7, 0.03, 0.022);
    const auto v = views();
    std::vector<CalibrationInput> inputs{
        {"a.png", photograph(board.image, board.width, board.height, truth, v[0])},
        {"b.png", photograph(board.image, board.width, board.height, truth, v[1])},
        {"blank.png", cv::Mat(720, 960, CV_32FC3, cv::Scalar::all(0.6))}};
    BoardSpec spec;
    spec.squares_x = 10, spec.squares_y = 7, spec.square_length = 0.03, spec.marker_length = 0.022;
    try {
        calibrate_camera(inputs, spec);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("at least 3"), std::string::npos) << message;
        EXPECT_NE(message.find("found it in 2 of 3"), std::string::npos) << message;
        EXPECT_NE(message.find("blank.png"), std::string::npos) << message;
    }
}

TEST(Calibration, BadBoardSpecsAreRejected) {
    BoardSpec spec;
    spec.squares_x = 7, spec.squares_y = 5, spec.square_length = 0.03, spec.marker_length = 0.04;
    EXPECT_THROW(validate(spec), Error);  // marker larger than the square
    spec.marker_length = 0.02;
    spec.squares_x = 20;
    EXPECT_NO_THROW(validate(spec));  // 20x5 squares hold 50 markers: exactly what 4X4_50 has
    spec.squares_y = 6;
    EXPECT_THROW(validate(spec), Error);  // 60 markers
    spec.squares_x = 2;
    EXPECT_THROW(validate(spec), Error);
    EXPECT_THROW(board_type_by_name("circles"), Error);
    // Sizes whose products overflow an int, or that would make OpenCV allocate or loop for ever, are refused with
    // the limit named (before any board is built).
    for (const int side : {201, 65536, 100000}) {
        spec.squares_x = spec.squares_y = side;
        try {
            validate(spec);
            FAIL() << side;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("--squares must be between 3 and 200"), std::string::npos) << e.what();
        }
    }
    spec.squares_x = 7, spec.squares_y = 5;
    spec.square_length = 1e39;  // beyond float
    EXPECT_THROW(validate(spec), Error);
    spec.square_length = 0.03;
    spec.dictionary = "/nonexistent/dictionary.yml";
    EXPECT_THROW(validate(spec), Error);
    spec.type = BoardType::Grid;
    spec.markers_x = 1, spec.markers_y = 1, spec.marker_separation = 0.01;
    EXPECT_THROW(validate(spec), Error);  // a grid of one marker is a marker
}

// A ChArUco board printed from a custom dictionary file (OpenCV's tutorial dictionary: 35 markers of 6x6 bits).
TEST(Calibration, ChArUcoBoardFromADictionaryFile) {
    const std::string dictionary = std::string(SURFSCATTER_SHARED_DATA) + "/realdata/photos/tutorial_dict.yml";
    const CameraModel truth = synthetic::true_camera();
    const auto board = synthetic::charuco_texture(7, 5, 0.04, 0.03, dictionary.c_str());
    std::vector<CalibrationInput> inputs;
    const auto all = views();
    for (std::size_t i = 0; i < 8; ++i)
        inputs.push_back({"view" + std::to_string(i), photograph(board.image, board.width, board.height, truth, all[i])});
    BoardSpec spec;
    spec.squares_x = 7, spec.squares_y = 5, spec.square_length = 0.04, spec.marker_length = 0.03;
    spec.dictionary = dictionary;
    const CalibrationResult result = calibrate_camera(inputs, spec);
    std::printf("[ measured ] ChArUco from tutorial_dict.yml: fx %.2f +- %.2f (true 1010), %zu of 8 views used\n",
                result.camera.fx(), result.camera.intrinsics_std_dev[0], result.used.size());
    EXPECT_EQ(result.used.size(), 8u);
    EXPECT_NEAR(result.camera.fx(), truth.fx(), 3 * result.camera.intrinsics_std_dev[0] + 0.5);
    spec.squares_x = 9, spec.squares_y = 8;  // 36 markers: one more than the file holds
    EXPECT_THROW(validate(spec), Error);
}

// Four near head-on views pin nothing down: the focal length's standard deviation is far above 1 % and the
// calibration says so, in the camera file too.
TEST(Calibration, WeakViewSetsAreFlagged) {
    const CameraModel truth = synthetic::true_camera();
    const auto board = synthetic::charuco_texture(10, 7, 0.03, 0.022);
    std::vector<CalibrationInput> inputs;
    int i = 0;
    for (const cv::Vec3d& eye : {cv::Vec3d{0.0, 0.0, 0.33}, {0.02, 0.0, 0.33}, {0.0, 0.02, 0.32}, {-0.02, 0.01, 0.34}})
        inputs.push_back({"near" + std::to_string(i++), photograph(board.image, board.width, board.height, truth,
                                                                   synthetic::look_at(eye, {0, 0, 0}, {0, 1, 0}))});
    BoardSpec spec;
    spec.squares_x = 10, spec.squares_y = 7, spec.square_length = 0.03, spec.marker_length = 0.022;
    const CalibrationResult weak = calibrate_camera(inputs, spec);
    std::printf("[ measured ] 4 head-on views: fx %.1f +- %.1f px, tilt span %.1f deg, %zu warnings\n", weak.camera.fx(),
                weak.camera.intrinsics_std_dev[0], weak.tilt_span_deg, weak.camera.calibration_warnings.size());
    EXPECT_LT(weak.tilt_span_deg, kMinimumTiltSpanDeg);
    ASSERT_FALSE(weak.camera.calibration_warnings.empty());
    const auto mentions = [&](const std::string& text) {
        for (const auto& w : weak.camera.calibration_warnings)
            if (w.find(text) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(mentions("fx = "));
    EXPECT_TRUE(mentions("span only"));
    EXPECT_TRUE(mentions("add views"));
    const auto path = std::filesystem::temp_directory_path() / ("weak_camera_" + std::to_string(::getpid()) + ".yml");
    write_camera(path, weak.camera);
    EXPECT_EQ(read_camera(path).calibration_warnings, weak.camera.calibration_warnings);
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace surfscatter::photo
