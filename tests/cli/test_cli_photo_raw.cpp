// The photo subcommands on camera RAW and EXIF-tagged photographs written by the test (photo/camera_files.hpp):
// the synthetic ArUco marker photograph (photo/synthetic.hpp) as a DNG from a camera with cross-talk and a
// non-neutral white, and as a JPEG with EXIF FocalLength. pose must find the camera and report the focal length;
// undistort must keep the RAW linear; a damaged RAW exits with status 2 naming the file.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <unistd.h>

#include "cli/cli_runner.hpp"
#include "photo/camera_files.hpp"
#include "photo/synthetic.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/colour_space.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {
namespace {

using test::run_cli;
namespace fs = std::filesystem;

constexpr double kMarkerLength = 0.05;
const cv::Vec3d kEye{-0.05, -0.18, 0.30};  // the camera, looking at the marker from the lower left
constexpr int kBackground = 170;  // 8-bit sRGB code of the table around the marker

class RawPhotos : public ::testing::Test {
protected:
    static fs::path dir;

    static void SetUpTestSuite() {
        dir = test::scratch_directory("surfscatter_photo_raw_cli_" + std::to_string(::getpid()));
        const CameraModel camera = synthetic::true_camera();
        write_camera(dir / "camera.yml", camera);
        const auto marker = synthetic::marker_texture(11, kMarkerLength);
        const cv::Mat gray = synthetic::render_plane(marker.image, marker.size, marker.size, camera,
                                                     synthetic::sub_pixel_rays(camera),
                                                     synthetic::look_at(kEye, {0, 0, 0}, {0, 1, 0}), kBackground);
        cv::Mat bgr8, rgb;
        cv::cvtColor(gray, bgr8, cv::COLOR_GRAY2BGR);
        cv::cvtColor(bgr8, rgb, cv::COLOR_BGR2RGB);
        rgb.convertTo(rgb, CV_32F, 1.0 / 255.0);
        auto raw_camera = camera_files::test_camera();
        raw_camera.focal_length_mm = 50.0;
        const auto dng = camera_files::dng_bytes(camera_files::bayer_mosaic(srgb_decode_image(rgb), raw_camera),
                                                 raw_camera);
        camera_files::write_file(dir / "marker.dng", dng);
        camera_files::write_file(dir / "marker.jpg", camera_files::jpeg_with_focal_length(bgr8, 35.0));
        cv::imwrite(path("marker.png"), gray);  // lossless, no EXIF: the reference for the other two
        camera_files::write_file(dir / "damaged.dng", {dng.begin(), dng.begin() + std::ptrdiff_t(dng.size() / 3)});
    }
    static void TearDownTestSuite() { fs::remove_all(dir); }

    static std::string path(const std::string& name) { return (dir / name).string(); }

    struct Pose {
        cv::Vec3d position;     // of the camera, metres
        double focal_mm = 0.0;  // EXIF focal length in pose.json, 0 when absent
    };
    static Pose pose(const std::string& photo) {
        const auto r = run_cli({"pose", path(photo), "--camera", path("camera.yml"), "--marker-length", "0.05", "-o",
                                path(photo + ".json")});
        EXPECT_EQ(r.exit_code, 0) << r.err;
        const auto j = nlohmann::json::parse(test::read_whole_file(path(photo + ".json")));
        return {{j["camera_position_m"][0], j["camera_position_m"][1], j["camera_position_m"][2]},
                j.value("exif_focal_length_mm", 0.0)};
    }
};
fs::path RawPhotos::dir;

TEST_F(RawPhotos, PoseReadsDngAndJpegAndReportsTheirFocalLengths) {
    const Pose png = pose("marker.png"), dng = pose("marker.dng"), jpeg = pose("marker.jpg");
    // The marker's corners in the demosaiced DNG must land where they are in the same picture saved losslessly;
    // the distance to the true camera is pose's own accuracy (2 mm, as in test_cli_photo.cpp).
    const double dng_shift = cv::norm(dng.position - png.position), jpeg_shift = cv::norm(jpeg.position - png.position);
    std::printf("[ measured ] pose from the DNG %.3f mm and from the JPEG %.3f mm away from the PNG's; PNG %.3f mm "
                "from the true camera\n",
                1e3 * dng_shift, 1e3 * jpeg_shift, 1e3 * cv::norm(png.position - kEye));
    EXPECT_LT(dng_shift, 1e-4);
    EXPECT_LT(jpeg_shift, 3e-4);
    EXPECT_LT(cv::norm(dng.position - kEye), 0.002);
    EXPECT_DOUBLE_EQ(dng.focal_mm, 50.0);
    EXPECT_DOUBLE_EQ(jpeg.focal_mm, 35.0);
    EXPECT_EQ(png.focal_mm, 0.0);
}

TEST_F(RawPhotos, UndistortKeepsTheRawLinear) {
    // --input-encoding applies to integer PNG/JPEG/TIFF only: a RAW is linear whatever it says.
    for (const char* encoding : {"srgb", "linear"}) {
        const auto r = run_cli({"undistort", path("marker.dng"), "--camera", path("camera.yml"), "--input-encoding",
                                encoding, "-o", path("undistorted.exr")});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const Photo out = read_photo(path("undistorted.exr"));
        // The table in the top-left corner: linear value of sRGB code 170, in all three channels.
        const cv::Scalar table = cv::mean(out.rgb(cv::Rect(40, 40, 32, 32)));
        const double expected = std::pow((kBackground / 255.0 + 0.055) / 1.055, 2.4);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(table[c], expected, 1e-3) << encoding << " channel " << c;
        std::printf("[ measured ] undistorted DNG, --input-encoding %s: table (%.5f, %.5f, %.5f), expected %.5f\n",
                    encoding, table[0], table[1], table[2], expected);
    }
}

TEST_F(RawPhotos, ADamagedRawExitsWithStatus2NamingIt) {
    const auto r = run_cli({"pose", path("damaged.dng"), "--camera", path("camera.yml"), "--marker-length", "0.05",
                            "-o", path("p.json")});
    EXPECT_EQ(r.exit_code, 2);
    // Cut before its Exif IFD (written after the pixels), the file fails already at LibRaw's header parsing.
    EXPECT_NE(r.err.find("surfscatter: error: camera RAW '" + path("damaged.dng") + "' could not be opened by LibRaw"),
              std::string::npos)
        << r.err;
}

}  // namespace
}  // namespace surfscatter::photo
