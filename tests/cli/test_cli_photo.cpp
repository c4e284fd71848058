// End-to-end tests of the photo subcommands on photographs synthesised with OpenCV (tests/photo/synthetic.hpp):
// a camera with known intrinsics and lens distortion photographs a ChArUco board, an ArUco marker and a
// ColorChecker under a colour cast; calibrate -> pose -> undistort -> colorcorrect -> compare must recover them.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

#include "cli/cli_runner.hpp"
#include "photo/synthetic.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {
namespace {

using test::run_cli;
namespace fs = std::filesystem;

CameraModel true_camera() {
    CameraModel c;
    c.image_size = {960, 720};
    c.matrix = cv::Matx33d(1010.0, 0.0, 487.5, 0.0, 1006.0, 352.2, 0.0, 0.0, 1.0);
    c.distortion = {-0.16, 0.09, 0.0012, -0.0008, 0.0};
    return c;
}
constexpr double kMarkerLength = 0.05;
const cv::Vec3d kPhotoEye{0.06, -0.22, 0.27};

class PhotoPipeline : public ::testing::Test {
protected:
    static fs::path dir;
    static std::vector<std::string> board_images;

    static void SetUpTestSuite() {
        dir = fs::temp_directory_path() / ("surfscatter_photo_cli_" + std::to_string(::getpid()));
        fs::create_directories(dir);
        const CameraModel camera = true_camera();
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

TEST_F(PhotoPipeline, ColorcorrectRemovesACastBelowTwoCiede2000) {
    const ChartReference reference = read_chart_reference();
    std::array<Vec3d, kChartPatches> patches;
    const cv::Matx33d cast(0.80, 0.10, -0.02, 0.04, 0.62, 0.08, -0.02, 0.06, 0.45);  // warm light, under-exposed
    for (std::size_t i = 0; i < patches.size(); ++i) {
        const auto& v = reference.linear_srgb[i];
        const cv::Vec3d c = cast * cv::Vec3d(std::clamp(v[0], 0.0, 1.0), std::clamp(v[1], 0.0, 1.0),
                                             std::clamp(v[2], 0.0, 1.0));
        patches[i] = {c[0], c[1], c[2]};
    }
    const std::array<cv::Point2f, 4> corners{cv::Point2f{200, 150}, {760, 170}, {745, 560}, {215, 545}};
    write_photo(path("chart.png"), synthetic::chart_photo(patches, {960, 720}, corners));

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
    const CameraModel camera = true_camera();
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
    expect_error(run_cli({"compare", path("marker.png"), path("broken.png"), "-o", path("s.png")}),
                 "could not be decoded");
}

}  // namespace
}  // namespace surfscatter::photo
