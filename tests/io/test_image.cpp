#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
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

namespace {

// Ward's RGBE encoding of an RGB triple (written here independently of the reader): the largest channel v = f 2^e
// with f in [0.5, 1) gives the shared exponent e + 128 and mantissas c 2^(8 - e).
std::array<std::uint8_t, 4> rgbe(float r, float g, float b) {
    const float v = std::max({r, g, b});
    if (v <= 0) return {0, 0, 0, 0};
    int e = 0;
    std::frexp(v, &e);
    const auto m = [&](float c) { return static_cast<std::uint8_t>(std::lround(std::ldexp(c, 8 - e))); };
    return {m(r), m(g), m(b), static_cast<std::uint8_t>(e + 128)};
}

}  // namespace

TEST(Image, RadianceHdrFlatAndRunLengthEncoded) {
    // 10 x 2 run-length encoded (new-style scanlines) and 4 x 1 flat, values exact in RGBE; EXPOSURE = 2 halves them.
    const auto pixel = [](int x, int y) {
        return std::array<float, 3>{0.5f, 0.25f * static_cast<float>(1 + x % 3), y == 0 ? 1.0f : 0.0f};
    };
    {
        std::ofstream out(temp_path("rle.hdr"), std::ios::binary);
        out << "#?RADIANCE\n# test\nFORMAT=32-bit_rle_rgbe\nEXPOSURE=2\n\n-Y 2 +X 10\n";
        for (int y = 0; y < 2; ++y) {
            std::array<std::array<std::uint8_t, 4>, 10> row{};
            for (int x = 0; x < 10; ++x) {
                const auto p = pixel(x, y);
                row[static_cast<std::size_t>(x)] = rgbe(p[0], p[1], p[2]);
            }
            out.put(2).put(2).put(0).put(10);
            for (std::size_t c = 0; c < 4; ++c) {
                // A run of the first four bytes, then the other six as literals.
                out.put(static_cast<char>(128 + 4)).put(static_cast<char>(row[0][c]));
                out.put(6);
                for (std::size_t x = 4; x < 10; ++x) out.put(static_cast<char>(row[x][c]));
            }
        }
    }
    // The runs repeat pixel 0's bytes over pixels 0-3, so the decoder must return pixel 0's value there.
    const Image rle = surfscatter::io::read_image(temp_path("rle.hdr"));
    ASSERT_EQ(rle.width, 10);
    ASSERT_EQ(rle.height, 2);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 10; ++x) {
            const auto p = pixel(x < 4 ? 0 : x, y);
            for (int c = 0; c < 3; ++c) EXPECT_EQ(rle.at(x, y, c), p[static_cast<std::size_t>(c)] / 2) << x << "," << y;
        }
    {
        std::ofstream out(temp_path("flat.hdr"), std::ios::binary);
        out << "#?RGBE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 4\n";
        for (int x = 0; x < 4; ++x) {
            const auto p = pixel(x, 0);
            for (std::uint8_t byte : rgbe(p[0], p[1], p[2])) out.put(static_cast<char>(byte));
        }
    }
    const Image flat = surfscatter::io::read_image(temp_path("flat.hdr"));
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(flat.at(x, 0, c), pixel(x, 0)[static_cast<std::size_t>(c)]);
    std::ofstream(temp_path("rotated.hdr")) << "#?RADIANCE\n\n+X 4 -Y 1\n";
    EXPECT_THROW(surfscatter::io::read_image(temp_path("rotated.hdr")), Error);
    std::ofstream(temp_path("short.hdr")) << "#?RADIANCE\n\n-Y 2 +X 4\nab";
    EXPECT_THROW(surfscatter::io::read_image(temp_path("short.hdr")), Error);
}

TEST(Image, GreyExrIsExpandedToRgb) {
    Image grey(3, 2, 1);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x) grey.at(x, y, 0) = static_cast<float>(0.25 * (x + 3 * y));
    const fs::path path = temp_path("grey.exr");
    surfscatter::io::write_exr(path, grey);
    const Image back = surfscatter::io::read_image(path);
    ASSERT_EQ(back.channels, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(x, y, c), grey.at(x, y, 0)) << x << "," << y << "," << c;
}
