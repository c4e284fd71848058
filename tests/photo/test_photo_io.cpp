#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/photo/undistort.hpp"

namespace surfscatter::photo {
namespace {

std::filesystem::path temp(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("surfscatter_photo_" + std::to_string(::getpid()) + "_" + name);
}

cv::Mat gradient(cv::Size size) {
    cv::Mat out(size, CV_32FC3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x)
            out.at<cv::Vec3f>(y, x) = {float(x) / float(size.width), float(y) / float(size.height), 0.25f};
    return out;
}

TEST(PhotoIo, RoundTripsThroughEveryFormat) {
    const cv::Mat linear = gradient({40, 30});
    for (const char* ext : {".png", ".tif", ".exr", ".jpg"}) {
        const auto path = temp(std::string("round") + ext);
        write_photo(path, linear);
        const Photo back = read_photo(path);
        ASSERT_EQ(back.rgb.size(), linear.size()) << ext;
        // Lossless formats: the worst sample (16-bit sRGB code values, float EXR); JPEG: the mean (lossy).
        const bool jpeg = std::string(ext) == ".jpg";
        const double tolerance = jpeg ? 0.01 : std::string(ext) == ".exr" ? 1e-7 : 1e-4;
        double worst = 0.0, sum = 0.0;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x)
                for (int c = 0; c < 3; ++c) {
                    const double d = std::abs(double(back.rgb.at<cv::Vec3f>(y, x)[c] - linear.at<cv::Vec3f>(y, x)[c]));
                    worst = std::max(worst, d);
                    sum += d / (30 * 40 * 3);
                }
        EXPECT_LT(jpeg ? sum : worst, tolerance) << ext;
        std::filesystem::remove(path);
    }
}

TEST(PhotoIo, SixteenBitLinearTiffIsReadAsLinear) {
    cv::Mat bgr16(4, 4, CV_16UC3, cv::Scalar(1000, 20000, 65535));
    const auto path = temp("linear.tif");
    ASSERT_TRUE(cv::imwrite(path.string(), bgr16));
    const Photo p = read_photo(path, Encoding::Linear);
    EXPECT_EQ(p.bit_depth, 16);
    const cv::Vec3f v = p.rgb.at<cv::Vec3f>(2, 2);
    EXPECT_NEAR(v[0], 1.0, 1e-6);              // R = 65535
    EXPECT_NEAR(v[2], 1000.0 / 65535.0, 1e-6);  // B
    std::filesystem::remove(path);
}

TEST(PhotoIo, BadFilesAreReported) {
    EXPECT_THROW(read_photo("/nonexistent/photo.png"), Error);
    const auto path = temp("garbage.png");
    std::ofstream(path) << "not a png";
    try {
        read_photo(path);
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("could not be decoded"), std::string::npos) << e.what();
    }
    std::filesystem::remove(path);
    EXPECT_THROW(read_photo(temp("x.bmp")), Error);
    EXPECT_THROW(encoding_by_name("gamma22"), Error);
}

TEST(CameraFile, RoundTripsAndRejectsBadFiles) {
    CameraModel c;
    c.image_size = {1280, 960};
    c.matrix = cv::Matx33d(1370, 0, 640.5, 0, 1371, 480.25, 0, 0, 1);
    c.distortion = {-0.1, 0.05, 0.001, -0.002, 0.0};
    c.rms_reprojection_error = 0.123;
    c.views = 12;
    c.intrinsics_std_dev = {0.4, 0.41, 0.5, 0.52, 1e-3, 2e-3, 1e-4, 1.1e-4, 3e-3};
    const auto path = temp("camera.yml");
    write_camera(path, c);
    const CameraModel back = read_camera(path);
    EXPECT_EQ(back.intrinsics_std_dev, c.intrinsics_std_dev);
    EXPECT_EQ(back.image_size, c.image_size);
    EXPECT_EQ(back.distortion, c.distortion);
    EXPECT_DOUBLE_EQ(back.fx(), 1370);
    EXPECT_DOUBLE_EQ(back.cy(), 480.25);
    EXPECT_DOUBLE_EQ(back.rms_reprojection_error, 0.123);
    EXPECT_EQ(back.views, 12);
    // A standard-deviation list that does not match the model is an error, not ignored.
    c.intrinsics_std_dev.pop_back();
    write_camera(path, c);
    EXPECT_THROW(read_camera(path), Error);
    std::ofstream(path) << "%YAML:1.0\n---\nimage_width: 10\n";
    EXPECT_THROW(read_camera(path), Error);
    std::filesystem::remove(path);
    EXPECT_THROW(read_camera(temp("missing.yml")), Error);
}

TEST(Undistort, StraightensALineBentByTheLens) {
    CameraModel c;
    c.image_size = {320, 240};
    c.matrix = cv::Matx33d(300, 0, 160, 0, 300, 120, 0, 0, 1);
    c.distortion = {-0.3, 0.1, 0, 0, 0};
    // Distorted image of a straight horizontal bright line y = 40 in the ideal image.
    std::vector<cv::Point3d> ideal;
    for (int x = 0; x < 320; ++x) ideal.emplace_back((x - 160) / 300.0, (40 - 120) / 300.0, 1.0);
    std::vector<cv::Point2d> distorted;
    cv::projectPoints(ideal, cv::Vec3d(), cv::Vec3d(), c.matrix, c.distortion, distorted);
    cv::Mat image(240, 320, CV_32FC3, cv::Scalar::all(0));
    for (const auto& p : distorted)
        if (p.x >= 0 && p.x < 320) image.at<cv::Vec3f>(cvRound(p.y), cvRound(p.x)) = {1, 1, 1};
    const cv::Mat straight = undistort_image(image, c);
    // In the undistorted image the line sits on y = 40 (within a pixel) across the centre.
    for (int x = 60; x < 260; x += 20) {
        int best = 0;
        float brightest = 0.0f;
        for (int y = 0; y < 240; ++y)
            if (straight.at<cv::Vec3f>(y, x)[0] > brightest) brightest = straight.at<cv::Vec3f>(y, x)[0], best = y;
        EXPECT_NEAR(best, 40, 1) << "x = " << x;
    }
    EXPECT_THROW(undistort_image(cv::Mat(100, 100, CV_32FC3), c), Error);
}

}  // namespace
}  // namespace surfscatter::photo
