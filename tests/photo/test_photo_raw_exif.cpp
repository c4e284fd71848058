// Camera RAW through LibRaw and EXIF FocalLength through libexif/libtiff, on files the tests write byte by byte
// (photo/camera_files.hpp): a DNG of six known colour patches seen by a camera with cross-talk and a non-neutral
// white, JPEG and TIFF photographs with an Exif IFD.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <unistd.h>

#include "photo/camera_files.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {
namespace {

namespace fs = std::filesystem;
using camera_files::write_file;

fs::path temp(const std::string& name) {
    return fs::temp_directory_path() / ("surfscatter_raw_" + std::to_string(::getpid()) + "_" + name);
}

constexpr int kPatch = 32;  // pixels; 3 x 2 patches
const std::array<cv::Vec3f, 6> kPatches{cv::Vec3f{0.18f, 0.18f, 0.18f}, cv::Vec3f{0.60f, 0.30f, 0.12f},
                                        cv::Vec3f{0.10f, 0.35f, 0.55f}, cv::Vec3f{0.85f, 0.80f, 0.70f},
                                        cv::Vec3f{0.05f, 0.25f, 0.08f}, cv::Vec3f{0.40f, 0.10f, 0.30f}};

cv::Mat patch_scene(float exposure) {
    cv::Mat scene(2 * kPatch, 3 * kPatch, CV_32FC3);
    for (int i = 0; i < 6; ++i)
        scene(cv::Rect(i % 3 * kPatch, i / 3 * kPatch, kPatch, kPatch)) = exposure * kPatches[i];
    return scene;
}

// Mean of the central half of patch i (away from the demosaicing seams between patches).
cv::Vec3d patch_mean(const cv::Mat& rgb, int i) {
    const cv::Scalar m = cv::mean(rgb(cv::Rect(i % 3 * kPatch + kPatch / 4, i / 3 * kPatch + kPatch / 4, kPatch / 2,
                                               kPatch / 2)));
    return {m[0], m[1], m[2]};
}

Photo read_dng(const std::string& name, float exposure, const camera_files::DngCamera& camera) {
    const fs::path path = temp(name);
    write_file(path, camera_files::dng_bytes(camera_files::bayer_mosaic(patch_scene(exposure), camera), camera));
    Photo photo = read_photo(path);
    fs::remove(path);
    return photo;
}

TEST(CameraRaw, DngDecodesToTheSceneInLinearSrgb) {
    auto camera = camera_files::test_camera();
    camera.focal_length_mm = 24.5;
    const Photo photo = read_dng("scene.dng", 1.0f, camera);
    ASSERT_EQ(photo.rgb.type(), CV_32FC3);
    ASSERT_EQ(photo.rgb.size(), cv::Size(3 * kPatch, 2 * kPatch));
    EXPECT_EQ(photo.bit_depth, 16);
    ASSERT_TRUE(photo.focal_length_mm.has_value());
    EXPECT_DOUBLE_EQ(*photo.focal_length_mm, 24.5);
    // White balance, black/white levels and the colour matrix undone: every patch comes back as the scene's
    // linear sRGB, 1 = the white level.
    double worst = 0.0;
    for (int i = 0; i < 6; ++i) {
        const cv::Vec3d got = patch_mean(photo.rgb, i);
        for (int c = 0; c < 3; ++c) {
            worst = std::max(worst, std::abs(got[c] - kPatches[i][c]));
            EXPECT_NEAR(got[c], kPatches[i][c], 2e-3) << "patch " << i << " channel " << c;
        }
    }
    std::printf("[ measured ] DNG -> linear sRGB: worst patch error %.2e (of values 0.05-0.85)\n", worst);
}

TEST(CameraRaw, OutputIsProportionalToTheRawSignal) {
    const auto camera = camera_files::test_camera();
    const Photo half = read_dng("half.dng", 0.5f, camera);
    const Photo full = read_dng("full.dng", 1.0f, camera);
    double worst = 0.0;
    for (int i = 0; i < 6; ++i) {
        const cv::Vec3d h = patch_mean(half.rgb, i), f = patch_mean(full.rgb, i);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(f[c] / h[c] - 2.0));
    }
    // The darkest samples (0.025 at half exposure, ~1500 raw counts) carry ~1e-3 of 16-bit rounding.
    EXPECT_LT(worst, 5e-3);
    std::printf("[ measured ] doubling the raw signal above black: output ratio 2 within %.2e\n", worst);
    EXPECT_FALSE(full.focal_length_mm.has_value());  // no Exif IFD, no focal length
}

TEST(CameraRaw, ARawFileUnderAnImageExtensionIsStillRead) {
    const auto camera = camera_files::test_camera();
    const fs::path path = temp("mislabelled.png");
    write_file(path, camera_files::dng_bytes(camera_files::bayer_mosaic(patch_scene(1.0f), camera), camera));
    const Photo photo = read_photo(path);
    fs::remove(path);
    EXPECT_NEAR(patch_mean(photo.rgb, 3)[1], kPatches[3][1], 2e-3);
}

void expect_error_naming(const fs::path& path, const std::string& words) {
    try {
        read_photo(path);
        FAIL() << "no error for " << path;
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_NE(message.find(words), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        std::printf("[ message  ] %s\n", message.c_str());
    }
}

TEST(CameraRaw, TruncatedOrForeignFilesAreErrorsNamingTheFile) {
    const auto camera = camera_files::test_camera();
    auto bytes = camera_files::dng_bytes(camera_files::bayer_mosaic(patch_scene(1.0f), camera), camera);
    const fs::path truncated = temp("truncated.dng");
    bytes.resize(bytes.size() / 2);  // the header survives, half of the pixels do not
    write_file(truncated, bytes);
    expect_error_naming(truncated, "could not be decoded by LibRaw");
    const fs::path text = temp("notes.nef");
    write_file(text, {'n', 'o', 't', ' ', 'a', ' ', 'r', 'a', 'w', ' ', 'f', 'i', 'l', 'e', '\n'});
    expect_error_naming(text, "could not be opened by LibRaw");
    const fs::path empty = temp("empty.cr2");
    write_file(empty, {});
    expect_error_naming(empty, "could not be opened by LibRaw");
    for (const auto& p : {truncated, text, empty}) fs::remove(p);
}

TEST(Exif, JpegFocalLengthIsReadWithTheImage) {
    const cv::Mat bgr(48, 64, CV_8UC3, cv::Scalar(40, 120, 200));
    const fs::path path = temp("exif.jpg");
    write_file(path, camera_files::jpeg_with_focal_length(bgr, 35.0));
    const Photo photo = read_photo(path);
    ASSERT_TRUE(photo.focal_length_mm.has_value());
    EXPECT_DOUBLE_EQ(*photo.focal_length_mm, 35.0);
    EXPECT_EQ(photo.rgb.size(), bgr.size());  // the APP1 segment does not disturb decoding
    // sRGB-decoded red channel of code 200 (the JPEG is lossy: a mean, 1e-2).
    EXPECT_NEAR(cv::mean(photo.rgb)[0], std::pow((200 / 255.0 + 0.055) / 1.055, 2.4), 1e-2);
    fs::remove(path);
}

TEST(Exif, TiffFocalLengthIsReadWithTheImage) {
    const cv::Mat rgb16(8, 6, CV_16UC3, cv::Scalar(65535, 32768, 1000));
    const fs::path path = temp("exif.tif");
    write_file(path, camera_files::tiff_with_focal_length(rgb16, 85.25));
    const Photo photo = read_photo(path, Encoding::Linear);
    ASSERT_TRUE(photo.focal_length_mm.has_value());
    EXPECT_NEAR(*photo.focal_length_mm, 85.25, 1e-5);  // libtiff may hand it back as float
    EXPECT_EQ(photo.bit_depth, 16);
    const cv::Vec3f px = photo.rgb.at<cv::Vec3f>(3, 2);
    EXPECT_NEAR(px[0], 1.0, 1e-6);
    EXPECT_NEAR(px[1], 32768.0 / 65535.0, 1e-6);
    EXPECT_NEAR(px[2], 1000.0 / 65535.0, 1e-6);
    fs::remove(path);
}

TEST(Exif, MissingOrMalformedExifGivesNoFocalLength) {
    const fs::path plain = temp("plain.jpg");
    ASSERT_TRUE(cv::imwrite(plain.string(), cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(128))));
    EXPECT_FALSE(read_exif_focal_length(plain).has_value());
    EXPECT_FALSE(read_photo(plain).focal_length_mm.has_value());
    // A zero focal length (0/100) is "unknown" in EXIF, not a lens.
    const fs::path zero = temp("zero.jpg");
    write_file(zero, camera_files::jpeg_with_focal_length(cv::Mat(8, 8, CV_8UC3, cv::Scalar::all(128)), 0.0));
    EXPECT_FALSE(read_exif_focal_length(zero).has_value());
    EXPECT_FALSE(read_exif_focal_length(temp("missing.jpg")).has_value());
    EXPECT_FALSE(read_exif_focal_length(temp("missing.tif")).has_value());
    for (const auto& p : {plain, zero}) fs::remove(p);
}

}  // namespace
}  // namespace surfscatter::photo
