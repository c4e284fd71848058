#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"

namespace fs = std::filesystem;
using surfscatter::Error;
using surfscatter::io::Image;

namespace {

fs::path temp_path(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / "surfscatter_test_io";
    fs::create_directories(dir);
    return dir / name;
}

Image gradient(int w, int h, int channels) {
    Image image(w, h, channels);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < channels; ++c)
                image.at(x, y, c) = static_cast<float>((x * 7 + y * 13 + c * 50) % 256) / 255.0f;
    return image;
}

}  // namespace

TEST(Image, PngRoundTripIsExactFor8BitValues) {
    for (int channels : {3, 4}) {
        const Image in = gradient(37, 21, channels);
        const fs::path path = temp_path("rt.png");
        surfscatter::io::write_image(path, in);
        const Image out = surfscatter::io::read_image(path);
        ASSERT_EQ(out.width, 37);
        ASSERT_EQ(out.height, 21);
        ASSERT_EQ(out.channels, channels);
        for (std::size_t i = 0; i < in.pixels.size(); ++i) ASSERT_NEAR(out.pixels[i], in.pixels[i], 1e-6);
    }
}

TEST(Image, PngClampsOutOfRangeAndNan) {
    Image in(2, 1, 3);
    in.pixels = {-1.0f, 2.0f, NAN, 0.5f, 1.0f, 0.0f};
    const fs::path path = temp_path("clamp.png");
    surfscatter::io::write_png(path, in);
    const Image out = surfscatter::io::read_image(path);
    EXPECT_EQ(out.pixels[0], 0.0f);
    EXPECT_EQ(out.pixels[1], 1.0f);
    EXPECT_EQ(out.pixels[2], 0.0f);
    EXPECT_NEAR(out.pixels[3], 128.0f / 255.0f, 1e-6);
}

TEST(Image, GreyPngIsExpandedToRgb) {
    Image in(4, 3, 1, 0.2f);
    const fs::path path = temp_path("grey.png");
    surfscatter::io::write_png(path, in);
    const Image out = surfscatter::io::read_image(path);
    ASSERT_EQ(out.channels, 3);
    EXPECT_NEAR(out.at(2, 1, 0), 51.0f / 255.0f, 1e-6);
    EXPECT_NEAR(out.at(2, 1, 2), 51.0f / 255.0f, 1e-6);
}

TEST(Image, ExrRoundTripIsBitExactInFloat) {
    for (int channels : {3, 4}) {
        Image in(19, 11, channels);
        for (std::size_t i = 0; i < in.pixels.size(); ++i) in.pixels[i] = 1e-3f * static_cast<float>(i * i) - 3.25f;
        const fs::path path = temp_path("rt.exr");
        surfscatter::io::write_image(path, in);
        const Image out = surfscatter::io::read_image(path);
        ASSERT_EQ(out.width, 19);
        ASSERT_EQ(out.height, 11);
        ASSERT_EQ(out.channels, channels);
        for (std::size_t i = 0; i < in.pixels.size(); ++i) ASSERT_EQ(out.pixels[i], in.pixels[i]);
    }
}

TEST(Image, JpegRoundTripIsCloseAtHighQuality) {
    Image in(64, 48, 3);
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x) {
            in.at(x, y, 0) = static_cast<float>(x) / 63.0f;
            in.at(x, y, 1) = static_cast<float>(y) / 47.0f;
            in.at(x, y, 2) = 0.5f;
        }
    const fs::path path = temp_path("rt.jpg");
    surfscatter::io::write_jpeg(path, in, 98);
    const Image out = surfscatter::io::read_image(path);
    ASSERT_EQ(out.channels, 3);
    double max_error = 0;
    for (std::size_t i = 0; i < in.pixels.size(); ++i)
        max_error = std::max(max_error, static_cast<double>(std::abs(out.pixels[i] - in.pixels[i])));
    EXPECT_LT(max_error, 0.03);  // smooth gradients survive quality-98 JPEG within a few code values
}

TEST(Image, ErrorsNameTheFile) {
    try {
        surfscatter::io::read_image(temp_path("does_not_exist.png"));
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("does_not_exist.png"), std::string::npos);
    }
    const fs::path bad = temp_path("garbage.png");
    std::ofstream(bad) << "this is not a png";
    EXPECT_THROW(surfscatter::io::read_image(bad), Error);
    const fs::path bad_jpeg = temp_path("garbage.jpg");
    std::ofstream(bad_jpeg) << "this is not a jpeg";
    EXPECT_THROW(surfscatter::io::read_image(bad_jpeg), Error);
    const fs::path bad_exr = temp_path("garbage.exr");
    std::ofstream(bad_exr) << "this is not an exr";
    EXPECT_THROW(surfscatter::io::read_image(bad_exr), Error);
    EXPECT_THROW(surfscatter::io::read_image(temp_path("x.tga")), Error);
    EXPECT_THROW(surfscatter::io::write_image(temp_path("x.bmp"), Image(2, 2, 3)), Error);
    EXPECT_THROW(Image(0, 2, 3), Error);
    EXPECT_THROW(Image(2, 2, 5), Error);
    EXPECT_THROW(surfscatter::io::write_image(temp_path("grey_alpha.jpg"), Image(2, 2, 2)), Error);
}
