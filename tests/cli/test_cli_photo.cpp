// End-to-end tests of the photo subcommands on photographs synthesised with OpenCV (tests/photo/synthetic.hpp):
// a camera with known intrinsics and lens distortion photographs a ChArUco board, an ArUco marker and a
// ColorChecker under a colour cast; calibrate -> pose -> undistort -> colorcorrect -> compare must recover them.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

#include "cli/cli_runner.hpp"
#include "photo/real_photos.hpp"
#include "photo/synthetic.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/pose.hpp"
#include "surfscatter/photo/undistort.hpp"

namespace surfscatter::photo {
namespace {

using test::run_cli;
namespace fs = std::filesystem;

constexpr double kMarkerLength = 0.05;
const cv::Vec3d kPhotoEye{0.06, -0.22, 0.27};

class PhotoPipeline : public ::testing::Test {
protected:
    static fs::path dir;
    static std::vector<std::string> board_images;

    static void SetUpTestSuite() {
        dir = fs::temp_directory_path() / ("surfscatter_photo_cli_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        const CameraModel camera = synthetic::true_camera();
        const cv::Mat rays = synthetic::sub_pixel_rays(camera);
        // Calibration views of a 10x7 ChArUco board (30 mm squares, 22 mm markers).
        const auto board = synthetic::charuco_texture(10, 7, 0.03, 0.022);
        const std::vector<std::pair<cv::Vec3d, cv::Vec3d>> eyes{
            {{0.0, -0.05, 0.33}, {0, 1, 0}}, {{0.16, 0.0, 0.30}, {0, 1, 0}},    {{-0.16, 0.02, 0.30}, {0, 1, 0}},
            {{0.0, 0.17, 0.28}, {0.3, 1, 0}}, {{0.0, -0.17, 0.28}, {-0.3, 1, 0}}, {{0.12, 0.12, 0.29}, {1, 1, 0}},
            {{-0.12, -0.1, 0.3}, {1, -1, 0}}, {{0.05, 0.0, 0.26}, {1, 0, 0}}};
        int i = 0;
        for (const auto& [eye, up] : eyes) {
            const auto view = synthetic::look_at(eye, {0, 0, 0}, up);
            const std::string path = (dir / ("board" + std::to_string(i++) + ".png")).string();
            cv::imwrite(path, synthetic::render_plane(board.image, board.width, board.height, camera, rays, view, 150));
            board_images.push_back(path);
        }
        for (const cv::Vec3d& target : {cv::Vec3d{0.07, 0.05, 0}, {-0.07, 0.05, 0}, {0.07, -0.05, 0}, {-0.07, -0.05, 0}}) {
            const auto view = synthetic::look_at(cv::Vec3d{0.0, 0.0, 0.22} + 0.3 * target, target, {0, 1, 0});
            const std::string path = (dir / ("board" + std::to_string(i++) + ".png")).string();
            cv::imwrite(path, synthetic::render_plane(board.image, board.width, board.height, camera, rays, view, 150));
            board_images.push_back(path);
        }
        // The photograph: the marker on a grey table, seen 35 cm away at about 40 degrees.
        const auto marker = synthetic::marker_texture(11, kMarkerLength);
        const cv::Mat gray = synthetic::render_plane(marker.image, marker.size, marker.size, camera, rays,
                                                     synthetic::look_at(kPhotoEye, {0, 0, 0}, {0, 1, 0}), 170);
        cv::imwrite((dir / "marker.png").string(), gray);
        cv::imwrite((dir / "blank.png").string(), cv::Mat(720, 960, CV_8UC1, cv::Scalar(128)));
        std::ofstream(dir / "broken.png") << "this is not an image";
    }
    static void TearDownTestSuite() { fs::remove_all(dir); }

    static std::string path(const std::string& name) { return (dir / name).string(); }

    static void calibrate() {
        if (fs::exists(path("camera.yml"))) return;
        const auto& b = board_images;
        ASSERT_EQ(b.size(), 12u);
        const auto r = run_cli({"calibrate", b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], b[8], b[9], b[10], b[11],
                                "--board", "charuco", "--squares", "10x7", "--square-length", "0.03",
                                "--marker-length", "0.022", "-o", path("camera.yml")});
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
};
fs::path PhotoPipeline::dir;
std::vector<std::string> PhotoPipeline::board_images;

TEST_F(PhotoPipeline, CalibrateThenPoseRecoversTheCameraWithin2mmAndHalfADegree) {
    calibrate();
    const CameraModel camera = read_camera(path("camera.yml"));
    EXPECT_NEAR(camera.fx(), 1010.0, 3.0);
    EXPECT_NEAR(camera.cy(), 352.2, 2.0);
    EXPECT_LT(camera.rms_reprojection_error, 0.15);

    const auto r = run_cli({"pose", path("marker.png"), "--camera", path("camera.yml"), "--marker-length",
                            "0.05", "-o", path("pose.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("<sensor type=\"perspective\">"), std::string::npos);
    const auto j = nlohmann::json::parse(test::read_whole_file(path("pose.json")));
    EXPECT_EQ(j["marker"]["id"], 11);
    const cv::Vec3d position(j["camera_position_m"][0], j["camera_position_m"][1], j["camera_position_m"][2]);
    const double position_error = cv::norm(position - kPhotoEye);
    // Rotation: the Mitsuba forward axis (third column of to_world) must look at the marker centre.
    const auto& m = j["mitsuba"]["to_world"];
    const cv::Vec3d forward(m[0][2], m[1][2], m[2][2]);
    const double angle = std::acos(std::clamp(forward.dot(cv::normalize(-kPhotoEye)), -1.0, 1.0)) * 180.0 / M_PI;
    const cv::Vec3d up(m[0][1], m[1][1], m[2][1]);
    const auto truth = synthetic::look_at(kPhotoEye, {0, 0, 0}, {0, 1, 0});
    cv::Matx33d r_true;
    cv::Rodrigues(truth.rvec, r_true);
    const cv::Vec3d true_up(-r_true(1, 0), -r_true(1, 1), -r_true(1, 2));  // minus OpenCV's image-down axis
    const double roll = std::acos(std::clamp(up.dot(true_up), -1.0, 1.0)) * 180.0 / M_PI;
    std::printf("[ measured ] end-to-end pose with the calibrated camera: position error %.3f mm, axis error %.4f "
                "deg, up error %.4f deg, reprojection %.3f px\n",
                1e3 * position_error, angle, roll, double(j["reprojection_rms_px"]));
    EXPECT_LT(position_error, 0.002);
    EXPECT_LT(angle, 0.5);
    EXPECT_LT(roll, 0.5);
    EXPECT_NEAR(double(j["mitsuba"]["fov_deg"]), 2.0 * std::atan(480.0 / 1010.0) * 180.0 / M_PI, 0.2);
}

TEST_F(PhotoPipeline, UndistortWritesPngAndExr) {
    calibrate();
    for (const char* name : {"undistorted.png", "undistorted.exr"}) {
        const auto r = run_cli({"undistort", path("marker.png"), "--camera", path("camera.yml"), "-o", path(name)});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Photo p = read_photo(path(name));
        EXPECT_EQ(p.rgb.size(), cv::Size(960, 720));
    }
}

// The chart's patches in linear light under warm light, under-exposed.
std::array<Vec3d, kChartPatches> cast_chart_patches() {
    const ChartReference reference = read_chart_reference();
    std::array<Vec3d, kChartPatches> patches;
    const cv::Matx33d cast(0.80, 0.10, -0.02, 0.04, 0.62, 0.08, -0.02, 0.06, 0.45);
    for (std::size_t i = 0; i < patches.size(); ++i) {
        const auto& v = reference.linear_srgb[i];
        const cv::Vec3d c = cast * cv::Vec3d(std::clamp(v[0], 0.0, 1.0), std::clamp(v[1], 0.0, 1.0),
                                             std::clamp(v[2], 0.0, 1.0));
        patches[i] = {c[0], c[1], c[2]};
    }
    return patches;
}
const std::array<cv::Point2f, 4> kChartCorners{cv::Point2f{200, 150}, {760, 170}, {745, 560}, {215, 545}};

TEST_F(PhotoPipeline, ColorcorrectRemovesACastBelowTwoCiede2000) {
    write_photo(path("chart.png"), synthetic::chart_photo(cast_chart_patches(), {960, 720}, kChartCorners));

    const auto detected = run_cli({"colorcorrect", path("chart.png"), "-o", path("corrected.png"), "--ccm",
                                   path("ccm.json")});
    ASSERT_EQ(detected.exit_code, 0) << detected.err;
    EXPECT_NE(detected.out.find("stage,mean_ciede2000,max_ciede2000"), std::string::npos);
    const auto j = nlohmann::json::parse(test::read_whole_file(path("ccm.json")));
    std::printf("[ measured ] colorcorrect (mcc): mean CIEDE2000 %.3f -> %.3f, max %.3f -> %.3f\n",
                double(j["ciede2000_before"]["mean"]), double(j["ciede2000_after"]["mean"]),
                double(j["ciede2000_before"]["max"]), double(j["ciede2000_after"]["max"]));
    EXPECT_GT(double(j["ciede2000_before"]["mean"]), 5.0);
    EXPECT_LT(double(j["ciede2000_after"]["mean"]), 2.0);
    EXPECT_TRUE(fs::exists(path("corrected.png")));

    const auto given = run_cli({"colorcorrect", path("chart.png"), "--chart-corners",
                                "200,150,760,170,745,560,215,545", "--preserve-white", "-o", path("corrected.exr"),
                                "--ccm", path("ccm2.json")});
    ASSERT_EQ(given.exit_code, 0) << given.err;
    const auto j2 = nlohmann::json::parse(test::read_whole_file(path("ccm2.json")));
    EXPECT_LT(double(j2["ciede2000_after"]["mean"]), 2.0);
    EXPECT_EQ(j2["chart_detection"], "given corners");
}

TEST_F(PhotoPipeline, CompareRanksTheWrongRenderingBelowTheRightOne) {
    // "Renderings" of the marker photo: the right one at another exposure, the wrong one from a camera 1 cm off.
    const CameraModel camera = synthetic::true_camera();
    const cv::Mat rays = synthetic::sub_pixel_rays(camera);
    const auto marker = synthetic::marker_texture(11, kMarkerLength);
    const auto photo_view = synthetic::look_at(kPhotoEye, {0, 0, 0}, {0, 1, 0});
    const auto wrong_view = synthetic::look_at(kPhotoEye + cv::Vec3d(0.01, 0, 0), {0, 0, 0}, {0, 1, 0});
    const cv::Mat photo8 = synthetic::render_plane(marker.image, marker.size, marker.size, camera, rays, photo_view, 170);
    const cv::Mat wrong8 = synthetic::render_plane(marker.image, marker.size, marker.size, camera, rays, wrong_view, 170);
    const auto to_linear = [](const cv::Mat& gray8, double gain) {
        cv::Mat rgb8, rgb;
        cv::cvtColor(gray8, rgb8, cv::COLOR_GRAY2RGB);
        rgb8.convertTo(rgb, CV_32F, 1.0 / 255.0);
        return cv::Mat(srgb_decode_image(rgb) * gain);
    };
    write_photo(path("photo.exr"), to_linear(photo8, 1.0));
    write_photo(path("right.exr"), to_linear(photo8, 3.0));
    write_photo(path("wrong.exr"), to_linear(wrong8, 3.0));
    const auto r = run_cli({"compare", path("photo.exr"), path("right.exr"), path("wrong.exr"), "--labels",
                            "right,wrong", "-o", path("sheet.png")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 3u) << r.out;
    EXPECT_EQ(lines[0], "label,render,exposure_scale,rmse,psnr_db,ssim,mean_ciede2000");
    EXPECT_TRUE(fs::exists(path("sheet.png")));
    EXPECT_TRUE(fs::exists(path("sheet.csv")));
    const auto j = nlohmann::json::parse(test::read_whole_file(path("sheet.json")));
    const auto& right = j["renders"][0];
    const auto& wrong = j["renders"][1];
    EXPECT_NEAR(double(right["exposure_scale"]), 1.0 / 3.0, 1e-4);
    EXPECT_LT(double(right["rmse"]), double(wrong["rmse"]));
    EXPECT_GT(double(right["ssim"]), double(wrong["ssim"]));
    EXPECT_LT(double(right["mean_ciede2000"]), double(wrong["mean_ciede2000"]));
}

TEST_F(PhotoPipeline, BadInputsExitWithStatus2AndSayWhy) {
    calibrate();
    const auto expect_error = [](const test::CliResult& r, const std::string& text) {
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
    };
    expect_error(run_cli({"pose", path("blank.png"), "--camera", path("camera.yml"), "--marker-length", "0.05", "-o",
                          path("p.json")}),
                 "no ArUco marker");
    expect_error(run_cli({"pose", path("broken.png"), "--camera", path("camera.yml"), "--marker-length", "0.05", "-o",
                          path("p.json")}),
                 "could not be decoded");
    expect_error(run_cli({"pose", path("marker.png"), "--camera", path("missing.yml"), "--marker-length", "0.05",
                          "-o", path("p.json")}),
                 "does not exist");
    expect_error(run_cli({"calibrate", board_images[0], board_images[1], path("blank.png"), "--squares", "10x7",
                          "--square-length", "0.03", "--marker-length", "0.022", "-o", path("c.yml")}),
                 "not found in: " + path("blank.png"));
    expect_error(run_cli({"calibrate", board_images[0], "--squares", "10by7", "--square-length", "0.03",
                          "--marker-length", "0.022", "-o", path("c.yml")}),
                 "--squares");
    expect_error(run_cli({"colorcorrect", path("blank.png"), "-o", path("x.png"), "--ccm", path("x.json")}),
                 "no ColorChecker chart found");
    expect_error(run_cli({"colorcorrect", path("blank.png"), "--chart-corners", "1,2,3", "-o", path("x.png"),
                          "--ccm", path("x.json")}),
                 "--chart-corners needs 8 numbers");
    expect_error(run_cli({"colorcorrect", path("blank.png"), "--fit", "l2", "-o", path("x.png"), "--ccm",
                          path("x.json")}),
                 "unknown colour-correction fit 'l2'");
    cv::imwrite(path("small.png"), cv::Mat(48, 64, CV_8UC3, cv::Scalar::all(128)));
    expect_error(run_cli({"colorcorrect", path("blank.png"), "--chart-corners", "10,10,500,10,500,300,10,300",
                          "--flat-field", path("small.png"), "-o", path("x.png"), "--ccm", path("x.json")}),
                 "flat field '" + path("small.png") + "' is 64x48 pixels but the photo is 960x720");
    expect_error(run_cli({"compare", path("marker.png"), path("broken.png"), "-o", path("s.png")}),
                 "could not be decoded");
}

// One line on stderr, naming every string in `names`, and exit status 2.
void expect_one_line_error(const test::CliResult& r, const std::vector<std::string>& names) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_EQ(r.err.rfind("surfscatter: error: ", 0), 0u) << r.err;
    for (const auto& name : names) EXPECT_NE(r.err.find(name), std::string::npos) << "'" << name << "' in " << r.err;
}

TEST_F(PhotoPipeline, BoardPoseHasTheBoardsCentreAsOrigin) {
    write_camera(path("true_camera.yml"), synthetic::true_camera());
    // board0.png: the 10x7 ChArUco board (centred on the world origin, its top towards +y) seen from (0, -0.05, 0.33).
    const auto r = run_cli({"pose", board_images[0], "--camera", path("true_camera.yml"), "--board", "charuco",
                            "--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "-o",
                            path("board_pose.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(test::read_whole_file(path("board_pose.json")));
    const cv::Vec3d position(j["camera_position_m"][0], j["camera_position_m"][1], j["camera_position_m"][2]);
    std::printf("[ measured ] ChArUco board pose: %d corners, camera %.3f mm from the truth, reprojection %.3f px, "
                "position std (%.3f, %.3f, %.3f) mm\n",
                int(j["board"]["corners_used"]), 1e3 * cv::norm(position - cv::Vec3d(0.0, -0.05, 0.33)),
                double(j["reprojection_rms_px"]), 1e3 * double(j["uncertainty"]["position_std_m"][0]),
                1e3 * double(j["uncertainty"]["position_std_m"][1]), 1e3 * double(j["uncertainty"]["position_std_m"][2]));
    EXPECT_LT(cv::norm(position - cv::Vec3d(0.0, -0.05, 0.33)), 5e-4);
    EXPECT_FALSE(bool(j["ambiguity"]["ambiguous"]));
    EXPECT_GE(int(j["board"]["corners_used"]), 40);
    // The Mitsuba up vector points to the board's top (+y), the camera looks at the origin.
    const auto& m = j["mitsuba"]["to_world"];
    EXPECT_GT(double(m[1][1]), 0.9);
    EXPECT_LT(cv::norm(cv::normalize(cv::Vec3d(m[0][2], m[1][2], m[2][2])) + cv::normalize(position)), 0.01);
}

TEST_F(PhotoPipeline, BoardPoseBadInputsExitWithStatus2AndOneLine) {
    write_camera(path("true_camera.yml"), synthetic::true_camera());
    const std::string camera = path("true_camera.yml");
    expect_one_line_error(run_cli({"pose", path("blank.png"), "--camera", camera, "--board", "charuco", "--squares",
                                   "10x7", "--square-length", "0.03", "--marker-length", "0.022", "-o", path("b.json")}),
                          {"board not found", "no marker of the ChArUco board"});
    // marker.png shows marker 11 alone: on a 4x3 grid board (ids 0-11) that is one marker, four corners.
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--board", "grid", "--markers",
                                   "4x3", "--marker-length", "0.05", "--marker-separation", "0.01", "-o",
                                   path("b.json")}),
                          {"too few board corners", "1 grid marker"});
    // Board options without a board, or a board that does not use them, are not ignored.
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--marker-length", "0.05",
                                   "--squares", "5x5", "-o", path("b.json")}),
                          {"--squares", "give --board too"});
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--board", "charuco", "--squares",
                                   "10x7", "--square-length", "0.03", "--marker-length", "0.022",
                                   "--marker-separation", "0.01", "-o", path("b.json")}),
                          {"--marker-separation does not apply to --board charuco"});
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--marker-length", "0.05",
                                   "--dictionary", path("missing_dictionary.yml"), "-o", path("b.json")}),
                          {"dictionary file", path("missing_dictionary.yml"), "does not exist"});
    std::ofstream(path("short_code.yml")) << "%YAML:1.0\nnmarkers: 1\nmarkersize: 4\nmarker_0: \"0101\"\n";
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--marker-length", "0.05",
                                   "--dictionary", path("short_code.yml"), "-o", path("b.json")}),
                          {path("short_code.yml"), "marker_0", "16 characters"});
    std::ofstream(path("not_yaml.yml")) << "nmarkers: [1, 2\n  : : ]]\n";
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--marker-length", "0.05",
                                   "--dictionary", path("not_yaml.yml"), "-o", path("b.json")}),
                          {path("not_yaml.yml")});
    expect_one_line_error(run_cli({"pose", path("marker.png"), "--camera", camera, "--marker-length", "0.05",
                                   "--dictionary", dir.string(), "-o", path("b.json")}),
                          {dir.string(), "is a directory"});
}

// Needs none of PhotoPipeline's rendered views: its own scratch directory.
TEST(PhotoCli, ColorcorrectLinearisesACameraCurvedJpeg) {
    const fs::path dir = test::scratch_directory("surfscatter_curved_chart_" + std::to_string(::getpid()));
    const auto path = [&](const std::string& name) { return (dir / name).string(); };
    // The chart under a warm cast, then a camera's S-curve on top of gamma 2.2, as an 8-bit JPEG.
    const cv::Mat light = synthetic::chart_photo(cast_chart_patches(), {960, 720}, kChartCorners);
    cv::Mat bgr8(light.size(), CV_8UC3);
    light.forEach<cv::Vec3f>([&](const cv::Vec3f& px, const int* pos) {
        for (int c = 0; c < 3; ++c) {
            const double y = std::pow(std::clamp(double(px[c]), 0.0, 1.0), 1 / 2.2);
            bgr8.at<cv::Vec3b>(pos[0], pos[1])[2 - c] =
                cv::saturate_cast<std::uint8_t>(255 * (0.5 + 0.5 * std::tanh(2.5 * (y - 0.5)) / std::tanh(1.25)));
        }
    });
    cv::imwrite(path("curved_chart.jpg"), bgr8, {cv::IMWRITE_JPEG_QUALITY, 92});
    const auto r = run_cli({"colorcorrect", path("curved_chart.jpg"), "-o", path("curved.png"), "--ccm",
                            path("curved.json")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(test::read_whole_file(path("curved.json")));
    std::printf("[ measured ] colorcorrect of an S-curve JPEG (auto: %s): mean CIEDE2000 %.3f -> %.3f\n",
                std::string(j["linearization"]["family"]).c_str(), double(j["ciede2000_before"]["mean"]),
                double(j["ciede2000_after"]["mean"]));
    EXPECT_EQ(j["linearization"]["family"], "poly");
    EXPECT_NE(r.err.find("linearisation poly"), std::string::npos) << r.err;
    EXPECT_LT(double(j["ciede2000_after"]["mean"]), 2.0);
    EXPECT_EQ(j["patch_pixels_rejected"].size(), 24u);
    const auto forced = run_cli({"colorcorrect", path("curved_chart.jpg"), "--linearize", "srgb", "-o",
                                 path("curved_srgb.png"), "--ccm", path("curved_srgb.json")});
    ASSERT_EQ(forced.exit_code, 0) << forced.err;
    const auto k = nlohmann::json::parse(test::read_whole_file(path("curved_srgb.json")));
    EXPECT_EQ(k["linearization"]["family"], "srgb");
    EXPECT_GT(double(k["ciede2000_after"]["mean"]), double(j["ciede2000_after"]["mean"]));
    expect_one_line_error(run_cli({"colorcorrect", path("curved_chart.jpg"), "--linearize", "log", "-o",
                                   path("x.png"), "--ccm", path("x.json")}),
                          {"linearisation 'log'"});
    fs::remove_all(dir);
}

// ---- The real photographs of OpenCV's ArUco tutorial (../shared/data/realdata/photos).
class RealPhotoCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir = fs::temp_directory_path() / ("surfscatter_real_photo_cli_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        write_camera(dir / "tutorial.yml", real_photos::tutorial_camera());
    }
    static void TearDownTestSuite() { fs::remove_all(dir); }
    static std::string path(const std::string& name) { return (dir / name).string(); }
    static fs::path dir;
};
fs::path RealPhotoCli::dir;

TEST_F(RealPhotoCli, GridBoardAndMarkerPosesWithTheDictionaryFile) {
    // The gap that fits the photo (test_real_photos.cpp): 8 mm between 40 mm markers.
    const auto board = run_cli({"pose", real_photos::kGridBoard, "--camera", path("tutorial.yml"), "--board", "grid",
                                "--markers", "5x7", "--marker-length", "0.04", "--marker-separation", "0.008",
                                "--dictionary", real_photos::kDictionary, "-o", path("board.json")});
    ASSERT_EQ(board.exit_code, 0) << board.err;
    const auto b = nlohmann::json::parse(test::read_whole_file(path("board.json")));
    EXPECT_EQ(int(b["board"]["markers_detected"]), 35);
    EXPECT_EQ(int(b["board"]["corners_used"]), 140);
    const cv::Vec3d board_camera(b["camera_position_m"][0], b["camera_position_m"][1], b["camera_position_m"][2]);
    // Marker 17 (row 3, column 2: the board's centre column) on its own.
    const auto marker = run_cli({"pose", real_photos::kGridBoard, "--camera", path("tutorial.yml"), "--marker-length",
                                 "0.04", "--dictionary", real_photos::kDictionary, "--marker-id", "17", "-o",
                                 path("marker17.json")});
    ASSERT_EQ(marker.exit_code, 0) << marker.err;
    const auto m = nlohmann::json::parse(test::read_whole_file(path("marker17.json")));
    EXPECT_EQ(m["marker"]["corner_refinement"], "pattern");
    EXPECT_TRUE(m.contains("uncertainty"));
    EXPECT_FALSE(bool(m["ambiguity"]["ambiguous"]));
    // Marker 17's centre in the board frame, from the board's layout.
    BoardSpec spec;
    spec.type = BoardType::Grid, spec.markers_x = 5, spec.markers_y = 7, spec.marker_length = 0.04;
    spec.marker_separation = 0.008, spec.dictionary = real_photos::kDictionary;
    const auto grid = make_grid_board(spec);
    const auto& o = grid->objPoints[17];
    const cv::Point3d centre = board_to_scene(spec, {0.5f * (o[0] + o[2])}).front();
    const cv::Vec3d single(m["camera_position_m"][0], m["camera_position_m"][1], m["camera_position_m"][2]);
    const double apart = cv::norm(single + cv::Vec3d(centre.x, centre.y, centre.z) - board_camera);
    std::printf("[ measured ] gboriginal.jpg via the CLI: marker 17 alone puts the camera %.1f mm from the grid board "
                "pose (%.0f mm away)\n", 1e3 * apart, 1e3 * cv::norm(board_camera));
    EXPECT_LT(apart, 0.05);
}

TEST_F(RealPhotoCli, AnAmbiguousMarkerIsRefusedUnlessAllowed) {
    // Marker 30 of gboriginal.jpg: 40 px, seen at 35 deg through a camera model that misfits the photo by ~2 px;
    // its mirror pose reprojects within 1.6 times the chosen one's error.
    const auto refused = run_cli({"pose", real_photos::kGridBoard, "--camera", path("tutorial.yml"), "--marker-length",
                                  "0.04", "--dictionary", real_photos::kDictionary, "--marker-id", "30", "-o",
                                  path("marker30.json")});
    expect_one_line_error(refused, {"marker 30", "ambiguous", "--allow-ambiguous"});
    EXPECT_FALSE(fs::exists(path("marker30.json")));
    const auto allowed = run_cli({"pose", real_photos::kGridBoard, "--camera", path("tutorial.yml"),
                                  "--marker-length", "0.04", "--dictionary", real_photos::kDictionary, "--marker-id",
                                  "30", "--allow-ambiguous", "-o", path("marker30.json")});
    ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
    EXPECT_NE(allowed.err.find("warning: the pose is ambiguous"), std::string::npos) << allowed.err;
    const auto j = nlohmann::json::parse(test::read_whole_file(path("marker30.json")));
    EXPECT_TRUE(bool(j["ambiguity"]["ambiguous"]));
    ASSERT_TRUE(j.contains("alternative"));
    EXPECT_TRUE(j["alternative"].contains("mitsuba"));
    EXPECT_GT(double(j["ambiguity"]["mirror_angle_deg"]), 10.0);
}

// ---- The end-to-end test: photographs rendered by `surfscatter render` (scenes/photo-setup, view 2, and
// ChArUco board scenes written here), then known lens distortion and a colour cast added with OpenCV.

constexpr int kRenderWidth = 1200, kRenderHeight = 900;
const std::vector<double> kLensDistortion{-0.12, 0.06, 0.0008, -0.0006, 0.0};

// The pinhole camera of a Mitsuba-style sensor with fov_axis x and no principal point offset, in OpenCV's terms.
CameraModel rendered_camera(double fov_deg) {
    CameraModel c;
    c.image_size = {kRenderWidth, kRenderHeight};
    const double f = 0.5 * kRenderWidth / std::tan(0.5 * fov_deg * M_PI / 180.0);
    c.matrix = cv::Matx33d(f, 0, 0.5 * kRenderWidth - 0.5, 0, f, 0.5 * kRenderHeight - 0.5, 0, 0, 1);
    c.distortion = kLensDistortion;
    return c;
}

// What a lens with `camera.distortion` would have recorded instead of the pinhole rendering `ideal`.
cv::Mat add_lens_distortion(const cv::Mat& ideal, const CameraModel& camera) {
    cv::Mat pixels(ideal.rows * ideal.cols, 1, CV_32FC2);
    for (int y = 0; y < ideal.rows; ++y)
        for (int x = 0; x < ideal.cols; ++x) pixels.at<cv::Vec2f>(y * ideal.cols + x) = {float(x), float(y)};
    cv::Mat undistorted;
    cv::undistortPoints(pixels, undistorted, camera.matrix, camera.distortion, cv::noArray(), camera.matrix,
                        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-10));
    cv::Mat map = undistorted.reshape(2, ideal.rows), out;
    cv::remap(ideal, out, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    return out;
}

struct LookAt {
    cv::Vec3d origin, target, up;
    double fov = 0.0;
};

// The sensor of scenes/photo-setup/view<N>.xml (read, not copied, so the test follows the scene).
LookAt read_view(int view) {
    const std::string xml = test::read_whole_file(std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/view" +
                                                  std::to_string(view) + ".xml");
    const auto triple = [&](const char* name) {
        std::smatch m;
        const std::regex re(std::string(name) + "=\"([^\"]+)\"");
        if (!std::regex_search(xml, m, re)) ADD_FAILURE() << "no " << name << " in view" << view << ".xml";
        std::string text = m[1];
        std::replace(text.begin(), text.end(), ',', ' ');
        std::istringstream in(text);
        cv::Vec3d v;
        in >> v[0] >> v[1] >> v[2];
        return v;
    };
    LookAt l{triple("origin"), triple("target"), triple("up")};
    std::smatch m;
    if (std::regex_search(xml, m, std::regex("name=\"fov\" value=\"([^\"]+)\""))) l.fov = std::stod(m[1]);
    return l;
}

// Edge of the marker's black square in scenes/photo-setup: the marker rectangle's half-size (its <scale>) times the
// dark fraction of its texture, both read from the scene, so that the test follows the scene as it is built.
double scene_marker_length() {
    const std::string dir = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/";
    const std::string xml = test::read_whole_file(dir + "scene.xml");
    std::smatch m;
    const std::regex marker_shape("<scale value=\"([0-9.eE+-]+)\"/>[\\s\\S]*?\"(textures/aruco[^\"]+)\"");
    if (!std::regex_search(xml, m, marker_shape)) {
        ADD_FAILURE() << "no marker rectangle in scene.xml";
        return 0.0;
    }
    const double half_size = std::stod(m[1]);
    const cv::Mat texture = cv::imread(dir + std::string(m[2]), cv::IMREAD_GRAYSCALE);
    cv::Mat dark;
    cv::compare(texture, 128, dark, cv::CMP_LT);
    const cv::Rect box = cv::boundingRect(dark);
    return 2.0 * half_size * box.width / texture.cols;
}

// Corners of the metal plate of scenes/photo-setup (a rectangle scaled by `s`, translated by x and z), in metres.
std::vector<cv::Point3d> scene_plate_corners() {
    const std::string xml = test::read_whole_file(std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml");
    std::smatch m;
    const std::regex plate("<scale value=\"([0-9.]+)\"/><translate x=\"([0-9.]+)\" z=\"([0-9.]+)\"/></transform>"
                           "\\s*<ref id=\"metal\"/>");
    if (!std::regex_search(xml, m, plate)) {
        ADD_FAILURE() << "no metal plate in scene.xml";
        return {};
    }
    const double half = std::stod(m[1]), x = std::stod(m[2]), z = std::stod(m[3]);
    return {{x - half, half, z}, {x + half, half, z}, {x + half, -half, z}, {x - half, -half, z}};
}

// Pixels (OpenCV convention) where the scene's sensor `view` with the pinhole of `camera` sees `points`.
std::vector<cv::Point2d> project_through_sensor(const LookAt& view, const CameraModel& camera,
                                                const std::vector<cv::Point3d>& points) {
    const cv::Vec3d forward = cv::normalize(view.target - view.origin);
    const cv::Vec3d down = -cv::normalize(view.up - view.up.dot(forward) * forward);
    const cv::Vec3d right = down.cross(forward);
    std::vector<cv::Point2d> pixels;
    for (const auto& p : points) {
        const cv::Vec3d d = cv::Vec3d(p.x, p.y, p.z) - view.origin;
        const double x = d.dot(right), y = d.dot(down), z = d.dot(forward);
        pixels.emplace_back(camera.fx() * x / z + camera.cx(), camera.fy() * y / z + camera.cy());
    }
    return pixels;
}

class RenderedPhotoPipeline : public ::testing::Test {
protected:
    static fs::path rdir;

    static std::string rpath(const std::string& name) { return (rdir / name).string(); }

    static void render(std::initializer_list<std::string> args) {
        const auto r = run_cli(args);
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }

    static void SetUpTestSuite() {
        rdir = fs::temp_directory_path() / ("surfscatter_photo_render_" + std::to_string(::getpid()));
        fs::create_directories(rdir);
    }
    static void TearDownTestSuite() { fs::remove_all(rdir); }
};
fs::path RenderedPhotoPipeline::rdir;

// About 1.5 min of CPU: 8 board renderings, the photograph at 32 spp (the marker's pose is limited by the render
// noise: 1.5 mm at 16 spp, 0.4 mm at 64 spp), its flat field and the two comparison renderings at 2-4 spp.
TEST_F(RenderedPhotoPipeline, CalibratePoseUndistortColorcorrectCompareOnRenderedPhotographs) {
    const LookAt view = read_view(2);
    ASSERT_GT(view.fov, 0.0);
    const CameraModel lens = rendered_camera(view.fov);
    const std::string scene = std::string(SURFSCATTER_SOURCE_DIR) + "/scenes/photo-setup/scene.xml";
    const std::string size_w = "width=" + std::to_string(kRenderWidth), size_h = "height=" + std::to_string(kRenderHeight);

    // 1. ChArUco board scenes (board texture written here), rendered, then seen through the lens.
    const auto board = synthetic::charuco_texture(10, 7, 0.03, 0.022);
    cv::imwrite(rpath("charuco.png"), board.image);
    const std::vector<std::pair<cv::Vec3d, cv::Vec3d>> eyes{
        {{0.0, -0.05, 0.45}, {0, 1, 0}},  {{0.2, 0.0, 0.42}, {0, 1, 0}},   {{-0.2, 0.02, 0.42}, {0, 1, 0}},
        {{0.0, 0.22, 0.4}, {0.3, 1, 0}},  {{0.0, -0.22, 0.4}, {-0.3, 1, 0}}, {{0.16, 0.16, 0.4}, {1, 1, 0}},
        {{-0.16, -0.13, 0.41}, {1, -1, 0}}, {{0.05, 0.0, 0.36}, {1, 0, 0}}};
    std::vector<std::string> boards;
    for (std::size_t i = 0; i < eyes.size(); ++i) {
        const auto& [eye, up] = eyes[i];
        const std::string xml = rpath("board" + std::to_string(i) + ".xml");
        std::ofstream(xml) << fmt::format(
            "<scene version=\"3.0.0\">\n"
            "  <integrator type=\"path\"><integer name=\"max_depth\" value=\"2\"/></integrator>\n"
            "  <sensor type=\"perspective\">\n"
            "    <float name=\"fov\" value=\"{}\"/><string name=\"fov_axis\" value=\"x\"/>\n"
            "    <transform name=\"to_world\"><lookat origin=\"{}, {}, {}\" target=\"0, 0, 0\" up=\"{}, {}, {}\"/>"
            "</transform>\n"
            "    <film type=\"hdrfilm\"><integer name=\"width\" value=\"{}\"/><integer name=\"height\" value=\"{}\"/>"
            "<rfilter type=\"box\"/></film>\n"
            "    <sampler type=\"independent\"><integer name=\"sample_count\" value=\"4\"/></sampler>\n"
            "  </sensor>\n"
            "  <emitter type=\"constant\"><rgb name=\"radiance\" value=\"1, 1, 1\"/></emitter>\n"
            "  <shape type=\"rectangle\">\n"
            "    <transform name=\"to_world\"><scale x=\"{}\" y=\"{}\" z=\"1\"/></transform>\n"
            "    <bsdf type=\"diffuse\"><texture name=\"reflectance\" type=\"bitmap\">"
            "<string name=\"filename\" value=\"charuco.png\"/>"
            "<transform name=\"to_uv\"><scale x=\"1\" y=\"-1\"/></transform></texture></bsdf>\n"
            "  </shape>\n"
            "</scene>\n",
            view.fov, eye[0], eye[1], eye[2], up[0], up[1], up[2], kRenderWidth, kRenderHeight, 0.5 * board.width,
            0.5 * board.height);
        const std::string exr = rpath("board" + std::to_string(i) + ".exr");
        render({"render", xml, "--quiet", "-o", exr});
        const std::string png = rpath("board" + std::to_string(i) + ".png");
        write_photo(png, add_lens_distortion(read_photo(exr).rgb, lens));
        boards.push_back(png);
    }
    const auto& b = boards;
    const auto cal = run_cli({"calibrate", b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7], "--squares", "10x7",
                              "--square-length", "0.03", "--marker-length", "0.022", "-o", rpath("camera.yml")});
    ASSERT_EQ(cal.exit_code, 0) << cal.err;
    const CameraModel camera = read_camera(rpath("camera.yml"));
    const auto& sd = camera.intrinsics_std_dev;
    ASSERT_EQ(sd.size(), 4 + camera.distortion.size());
    std::printf("[ measured ] rendered boards: fx %.2f +- %.2f fy %.2f +- %.2f cx %.2f +- %.2f cy %.2f +- %.2f (true "
                "%.2f, %.2f, %.2f), RMS %.3f px\n",
                camera.fx(), sd[0], camera.fy(), sd[1], camera.cx(), sd[2], camera.cy(), sd[3], lens.fx(), lens.cx(),
                lens.cy(), camera.rms_reprojection_error);
    EXPECT_LT(std::abs(camera.fx() - lens.fx()), 3 * sd[0]);
    EXPECT_LT(std::abs(camera.cx() - lens.cx()), 3 * sd[2]);
    EXPECT_LT(std::abs(camera.cy() - lens.cy()), 3 * sd[3]);

    // 2. The photograph: view 2 of the photo set-up through the lens, with a colour cast; and its flat field (a grey
    // card in the chart's place, same camera and light).
    render({"render", scene, "-D", "view=2", "-D", "model=conductor", "-D", size_w, "-D", size_h, "--spp", "32",
            "--quiet", "-o", rpath("view2.exr")});
    render({"render", scene, "-D", "view=2", "-D", "model=conductor", "-D", "chart=greycard", "-D", size_w, "-D",
            size_h, "--spp", "4", "--quiet", "-o", rpath("flat.exr")});
    render({"render", scene, "-D", "view=2", "-D", "model=conductor", "-D", size_w, "-D", size_h, "--spp", "2",
            "--seed", "7", "--quiet", "-o", rpath("right.exr")});  // same seed as wrong.exr: only the metal differs
    render({"render", scene, "-D", "view=2", "-D", "model=conductor", "-D", "material=Cu", "-D", size_w, "-D",
            size_h, "--spp", "2", "--seed", "7", "--quiet", "-o", rpath("wrong.exr")});
    const cv::Matx33f cast(0.85f, 0.08f, 0.0f, 0.03f, 0.7f, 0.06f, 0.0f, 0.05f, 0.5f);
    cv::Mat photo;
    cv::transform(add_lens_distortion(read_photo(rpath("view2.exr")).rgb, lens), photo, cast);
    write_photo(rpath("photo.png"), photo);
    cv::Mat flat;
    cv::transform(add_lens_distortion(read_photo(rpath("flat.exr")).rgb, lens), flat, cast);
    write_photo(rpath("flat.png"), flat);

    // 3. Pose with the calibrated camera against the scene's own sensor. (The marker lies 0.2 mm above the mat, which
    // the scene's frame has at z = 0: that much of the error is the scene's.) The clean rendering seen through the
    // exact pinhole camera is measured too: it separates the pose's own error from the calibration's.
    const double marker_length = scene_marker_length();
    const std::string length = fmt::format("{}", marker_length);
    CameraModel pinhole = lens;
    pinhole.distortion.assign(5, 0.0);
    write_camera(rpath("pinhole.yml"), pinhole);
    const auto clean_pose = run_cli({"pose", rpath("view2.exr"), "--camera", rpath("pinhole.yml"), "--marker-length",
                                     length, "-o", rpath("clean_pose.json")});
    ASSERT_EQ(clean_pose.exit_code, 0) << clean_pose.err;
    const auto pose = run_cli({"pose", rpath("photo.png"), "--camera", rpath("camera.yml"), "--marker-length", length,
                               "-o", rpath("pose.json")});
    ASSERT_EQ(pose.exit_code, 0) << pose.err;
    const auto j = nlohmann::json::parse(test::read_whole_file(rpath("pose.json")));
    const auto c = nlohmann::json::parse(test::read_whole_file(rpath("clean_pose.json")));
    const auto vec = [](const nlohmann::json& a) { return cv::Vec3d(a[0], a[1], a[2]); };
    const auto column = [](const nlohmann::json& m, int k) { return cv::Vec3d(m[0][k], m[1][k], m[2][k]); };
    const auto angle = [](const cv::Vec3d& u, const cv::Vec3d& v) {
        return std::acos(std::clamp(u.dot(cv::normalize(v)), -1.0, 1.0)) * 180.0 / M_PI;
    };
    // The scene's sensor: Mitsuba's lookat, z toward the target, y the up vector made orthogonal to it.
    const cv::Vec3d axis = cv::normalize(view.target - view.origin);
    const cv::Vec3d up = cv::normalize(view.up - view.up.dot(axis) * axis);
    const auto report = [&](const char* what, const nlohmann::json& p) {
        const double position_error = cv::norm(vec(p["camera_position_m"]) - view.origin);
        const double axis_error = angle(axis, column(p["mitsuba"]["to_world"], 2));
        const double up_error = angle(up, column(p["mitsuba"]["to_world"], 1));
        std::printf("[ measured ] %s (marker %.4f m): position error %.3f mm, optical axis %.4f deg, up %.4f deg, "
                    "corners by %s\n",
                    what, marker_length, 1e3 * position_error, axis_error, up_error,
                    std::string(p["marker"]["corner_refinement"]).c_str());
        EXPECT_LT(position_error, 0.002) << what;
        EXPECT_LT(axis_error, 0.5) << what;
        EXPECT_LT(up_error, 0.5) << what;
    };
    report("clean rendering, exact pinhole camera", c);
    report("photograph (lens, cast), calibrated camera", j);

    // 4. Undistort, colour-correct on the chart (mcc), compare against the right and a wrong rendering.
    const auto und = run_cli({"undistort", rpath("photo.png"), "--camera", rpath("camera.yml"), "-o",
                              rpath("undistorted.exr")});
    ASSERT_EQ(und.exit_code, 0) << und.err;
    const auto und_flat = run_cli({"undistort", rpath("flat.png"), "--camera", rpath("camera.yml"), "-o",
                                   rpath("flat_undistorted.exr")});
    ASSERT_EQ(und_flat.exit_code, 0) << und_flat.err;
    const auto cc = run_cli({"colorcorrect", rpath("undistorted.exr"), "--flat-field", rpath("flat_undistorted.exr"),
                             "-o", rpath("corrected.exr"), "--ccm", rpath("ccm.json")});
    ASSERT_EQ(cc.exit_code, 0) << cc.err;
    const auto ccm = nlohmann::json::parse(test::read_whole_file(rpath("ccm.json")));
    // The target, mean CIEDE2000 below 2 on the chart, needs the flat field: the point lamp lights the chart
    // unevenly, which no 3x3 matrix can undo (reported below as "without flat field"). What remains is the chart's
    // colour inconstancy: spectral albedos under 2700 K, white-balanced.
    std::printf("[ measured ] rendered chart: mean CIEDE2000 %.3f -> %.3f, max %.3f -> %.3f (%s; without the flat "
                "field: mean %.3f, max %.3f)\n",
                double(ccm["ciede2000_before"]["mean"]), double(ccm["ciede2000_after"]["mean"]),
                double(ccm["ciede2000_before"]["max"]), double(ccm["ciede2000_after"]["max"]),
                std::string(ccm["fit"]).c_str(), double(ccm["ciede2000_after_without_flat_field"]["mean"]),
                double(ccm["ciede2000_after_without_flat_field"]["max"]));
    EXPECT_GT(double(ccm["ciede2000_before"]["mean"]), 8.0);
    EXPECT_LT(double(ccm["ciede2000_after"]["mean"]), 2.0);

    // Compare on the metal plate (where the two renderings differ), as far as the undistorted photo has data there.
    const cv::Mat covered = undistort_image(cv::Mat(kRenderHeight, kRenderWidth, CV_32FC1, cv::Scalar(1)), camera);
    cv::Mat mask, plate(kRenderHeight, kRenderWidth, CV_8UC1, cv::Scalar(0));
    cv::compare(covered, 0.999, mask, cv::CMP_GT);
    std::vector<cv::Point> outline;
    for (const cv::Point2d& p : project_through_sensor(view, lens, scene_plate_corners())) outline.emplace_back(p);
    cv::fillConvexPoly(plate, outline, cv::Scalar(255));
    cv::bitwise_and(mask, plate, mask);
    ASSERT_GT(cv::countNonZero(mask), 2000);
    cv::imwrite(rpath("mask.png"), mask);
    const auto cmp = run_cli({"compare", rpath("corrected.exr"), rpath("right.exr"), rpath("wrong.exr"), "--mask",
                              rpath("mask.png"), "--labels", "Al (right),Cu (wrong)", "-o", rpath("sheet.png")});
    ASSERT_EQ(cmp.exit_code, 0) << cmp.err;
    const auto metrics = nlohmann::json::parse(test::read_whole_file(rpath("sheet.json")));
    const auto& right = metrics["renders"][0];
    const auto& wrong = metrics["renders"][1];
    std::printf("[ measured ] rendered compare: right RMSE %.4g SSIM %.4f dE00 %.3f | wrong RMSE %.4g SSIM %.4f "
                "dE00 %.3f\n",
                double(right["rmse"]), double(right["ssim"]), double(right["mean_ciede2000"]), double(wrong["rmse"]),
                double(wrong["ssim"]), double(wrong["mean_ciede2000"]));
    EXPECT_LT(double(right["rmse"]), double(wrong["rmse"]));
    EXPECT_LT(double(right["mean_ciede2000"]), double(wrong["mean_ciede2000"]));
    EXPECT_GT(double(right["psnr_db"]), double(wrong["psnr_db"]));
}

}  // namespace
}  // namespace surfscatter::photo

// A photo of 6X6_250 markers with the default dictionary 4X4_50 "finds" a false marker whose pose is ambiguous: the
// message names the dictionary that fits. OpenCV's own camera file (camera_matrix and distortion_coefficients only)
// takes its image size from the photo.
TEST(CliPhoto, PoseNamesTheDictionaryThatFitsAndTakesTheImageSizeFromThePhoto) {
    const std::filesystem::path photos = std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "photos";
    const std::string jpg = (photos / "singlemarkersoriginal.jpg").string();
    const std::string camera = (photos / "tutorial_camera_params.yml").string();
    const std::string out = (std::filesystem::temp_directory_path() / "surfscatter_cli_pose_dictionary.json").string();
    auto r = surfscatter::test::run_cli({"pose", jpg, "--camera", camera, "--marker-length", "0.05", "-o", out});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("markers of dictionary 6X6_250"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("of 4X4_50: pass --dictionary 6X6_250"), std::string::npos) << r.err;
    r = surfscatter::test::run_cli({"pose", jpg, "--camera", camera, "--marker-length", "0.05", "--dictionary", "6X6_250", "-o", out});
    EXPECT_NE(r.err.find("several markers found"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("image_width"), std::string::npos) << r.err;
    r = surfscatter::test::run_cli({"undistort", jpg, "--camera", camera, "-o",
                 (std::filesystem::temp_directory_path() / "surfscatter_cli_undistort_nosize.exr").string()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::filesystem::remove(out);
    std::filesystem::remove(std::filesystem::temp_directory_path() / "surfscatter_cli_undistort_nosize.exr");
}
