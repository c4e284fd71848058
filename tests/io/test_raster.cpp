// io/raster.hpp: round trips through libpng, libjpeg and libtiff, and the errors on damaged files. The samples are
// checked against OpenCV's decoders in tests/photo/test_raster_vs_opencv.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include <zlib.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/io/raster.hpp"

namespace fs = std::filesystem;
using namespace surfscatter;
using io::Raster;
using io::RasterFormat;

namespace {

fs::path temp_path(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / "surfscatter_test_raster";
    fs::create_directories(dir);
    return dir / name;
}

// Noise over the whole range (exercises every bit) for lossless formats; a smooth pattern for JPEG.
Raster noise(int width, int height, int channels, int depth, unsigned seed) {
    Raster raster(width, height, channels, depth);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> sample(0, depth == 16 ? 65535 : 255);
    for (auto& s : raster.samples) s = static_cast<std::uint16_t>(sample(rng));
    return raster;
}

Raster smooth(int width, int height, int channels) {
    Raster raster(width, height, channels, 8);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < channels; ++c)
                raster.at(x, y, c) = static_cast<std::uint16_t>(128 + 100 * std::sin(0.11 * x + 0.07 * y + c));
    return raster;
}

// libtiff's RGBA reader (OpenCV's too) multiplies the colour of an 8-bit TIFF with unassociated alpha by the alpha.
std::vector<std::uint16_t> premultiplied(const Raster& rgba) {
    std::vector<std::uint16_t> samples = rgba.samples;
    for (std::size_t p = 0; p < samples.size(); p += 4)
        for (std::size_t c = 0; c < 3; ++c)
            samples[p + c] = static_cast<std::uint16_t>((samples[p + c] * samples[p + 3] + 127) / 255);
    return samples;
}

std::string file_bytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

// Reading `path` fails with a RasterError: one line naming the file, and nothing printed by the libraries.
io::RasterError expect_raster_error(const fs::path& path) {
    testing::internal::CaptureStderr();
    try {
        io::read_raster(path);
    } catch (const io::RasterError& e) {
        const std::string printed = testing::internal::GetCapturedStderr();
        EXPECT_EQ(printed, "") << path;
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_FALSE(e.reason.empty());
        return e;
    }
    testing::internal::GetCapturedStderr();
    ADD_FAILURE() << path << " was decoded";
    return io::RasterError(path, "", false);
}

}  // namespace

TEST(Raster, LosslessRoundTripsKeepEverySample) {
    for (const auto& [format, name] : {std::pair{RasterFormat::png, "rt.png"}, std::pair{RasterFormat::tiff, "rt.tif"}})
        for (int depth : {8, 16})
            for (int channels : {1, 3, 4}) {
                const Raster in = noise(53, 29, channels, depth, static_cast<unsigned>(channels * depth));
                const fs::path path = temp_path(name);
                io::write_raster(path, in, format);
                const Raster back = io::read_raster(path);
                EXPECT_EQ(back.width, 53);
                EXPECT_EQ(back.height, 29);
                EXPECT_EQ(back.channels, channels) << name << " " << depth;
                EXPECT_EQ(back.bit_depth, depth) << name;
                EXPECT_EQ(back.samples, format == RasterFormat::tiff && depth == 8 && channels == 4 ? premultiplied(in)
                                                                                                  : in.samples)
                    << name << " " << depth << "-bit, " << channels << " channels";
                EXPECT_EQ(back.warnings, "");
            }
}

TEST(Raster, EightBitPngsCarryAnSrgbChunkSixteenBitOnesNone) {
    // As libpng's simplified writer made the film's PNGs before (the render's PNG is byte for byte the same,
    // docs/PERFORMANCE.md); 16-bit photographs carry no colour chunk, as OpenCV wrote them.
    const fs::path path = temp_path("srgb.png");
    io::write_raster(path, noise(8, 4, 3, 8, 2), RasterFormat::png);
    EXPECT_NE(file_bytes(path).find("sRGB"), std::string::npos);
    io::write_raster(path, noise(8, 4, 3, 16, 2), RasterFormat::png);
    EXPECT_EQ(file_bytes(path).find("sRGB"), std::string::npos);
}

TEST(Raster, GreyWithAlphaComesBackAsRgba) {
    // As OpenCV's imread(IMREAD_UNCHANGED): a grey + alpha PNG is 4 channels, the grey copied to R, G and B.
    const Raster in = noise(17, 11, 2, 16, 7);
    const fs::path path = temp_path("ga.png");
    io::write_raster(path, in, RasterFormat::png);
    const Raster back = io::read_raster(path);
    ASSERT_EQ(back.channels, 4);
    for (int y = 0; y < 11; ++y)
        for (int x = 0; x < 17; ++x) {
            for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(x, y, c), in.at(x, y, 0));
            EXPECT_EQ(back.at(x, y, 3), in.at(x, y, 1));
        }
}

TEST(Raster, JpegRoundTripIsCloseAtQuality95) {
    for (int channels : {1, 3}) {
        const Raster in = smooth(64, 48, channels);
        const fs::path path = temp_path("rt.jpg");
        io::write_raster(path, in, RasterFormat::jpeg, 95);
        const Raster back = io::read_raster(path);
        ASSERT_EQ(back.channels, channels);
        EXPECT_EQ(back.bit_depth, 8);
        double worst = 0, sum = 0;
        for (std::size_t i = 0; i < in.samples.size(); ++i) {
            const double d = std::abs(double(back.samples[i]) - double(in.samples[i]));
            worst = std::max(worst, d);
            sum += d;
        }
        // Quality 95 on a smooth pattern: about half a level on average (4:2:0 chroma costs colour a little more).
        EXPECT_LT(sum / double(in.samples.size()), 1.5) << channels;
        EXPECT_LT(worst, 12) << channels;
    }
}

TEST(Raster, WritingWhatAFormatCannotHoldIsAnError) {
    EXPECT_THROW(io::write_raster(temp_path("a.jpg"), noise(4, 4, 4, 8, 1), RasterFormat::jpeg), Error);
    EXPECT_THROW(io::write_raster(temp_path("a.jpg"), noise(4, 4, 3, 16, 1), RasterFormat::jpeg), Error);
    EXPECT_THROW(io::write_raster(temp_path("a.jpg"), noise(4, 4, 3, 8, 1), RasterFormat::jpeg, 0), Error);
    Raster wrong = noise(4, 4, 3, 8, 1);
    wrong.samples.pop_back();
    EXPECT_THROW(io::write_raster(temp_path("a.png"), wrong, RasterFormat::png), Error);
    EXPECT_THROW(io::write_raster("/nonexistent/dir/a.png", noise(4, 4, 3, 8, 1), RasterFormat::png), Error);
    EXPECT_THROW(io::write_raster("/nonexistent/dir/a.tif", noise(4, 4, 3, 8, 1), RasterFormat::tiff), Error);
}

TEST(Raster, TruncatedFilesAreOneClearError) {
    for (const auto& [format, name] : {std::pair{RasterFormat::png, "cut.png"}, std::pair{RasterFormat::jpeg, "cut.jpg"},
                                       std::pair{RasterFormat::tiff, "cut.tif"}}) {
        const fs::path path = temp_path(name);
        io::write_raster(path, noise(120, 80, 3, 8, 3), format);
        const std::string whole = file_bytes(path);
        write_bytes(path, whole.substr(0, whole.size() / 2));
        const io::RasterError e = expect_raster_error(path);
        // libjpeg would fill the rest of a truncated JPEG with grey and only warn: the reader makes it an error.
        if (format == RasterFormat::jpeg) {
            EXPECT_TRUE(e.truncated);
            EXPECT_NE(e.reason.find("Premature end of JPEG file"), std::string::npos) << e.reason;
        }
    }
}

TEST(Raster, CorruptAndForeignFilesAreOneClearError) {
    std::mt19937 rng(11);
    for (const auto& [format, name] : {std::pair{RasterFormat::png, "bad.png"}, std::pair{RasterFormat::jpeg, "bad.jpg"},
                                       std::pair{RasterFormat::tiff, "bad.tif"}}) {
        const fs::path path = temp_path(name);
        io::write_raster(path, noise(40, 30, 3, 8, 5), format);
        std::string bytes = file_bytes(path);
        // Keep the signature, scramble the rest: the header or the data must be found bad.
        for (std::size_t i = 8; i < bytes.size(); ++i) bytes[i] = static_cast<char>(rng());
        write_bytes(path, bytes);
        expect_raster_error(path);
    }
    const fs::path text = temp_path("text.png");
    write_bytes(text, "not an image at all");
    EXPECT_NE(expect_raster_error(text).reason.find("not a PNG, JPEG or TIFF"), std::string::npos);
    write_bytes(text, "");
    expect_raster_error(text);
    EXPECT_THROW(io::read_raster(temp_path("missing.png")), Error);
    EXPECT_THROW(io::read_raster(fs::temp_directory_path()), Error);
}

void put_big_endian(std::string& bytes, std::size_t at, std::uint32_t value, int count) {
    for (int i = 0; i < count; ++i) bytes[at + i] = static_cast<char>(value >> (8 * (count - 1 - i)));
}

TEST(Raster, AHeaderClaimingMorePixelsThanTheFileCanHoldFailsBeforeAllocating) {
    // 60000 x 60000 RGB: 10.8 GB of samples, from a file of a few hundred bytes.
    const fs::path png = temp_path("huge.png");
    io::write_raster(png, noise(16, 16, 3, 8, 1), RasterFormat::png);
    std::string bytes = file_bytes(png);
    put_big_endian(bytes, 16, 60000, 4);  // IHDR width, height
    put_big_endian(bytes, 20, 60000, 4);
    const auto crc = crc32(0, reinterpret_cast<const Bytef*>(bytes.data() + 12), 17);  // chunk type and data
    put_big_endian(bytes, 29, static_cast<std::uint32_t>(crc), 4);
    write_bytes(png, bytes);
    EXPECT_NE(expect_raster_error(png).reason.find("60000x60000 PNG image needs"), std::string::npos);

    const fs::path jpeg = temp_path("huge.jpg");
    io::write_raster(jpeg, smooth(16, 16, 3), RasterFormat::jpeg);
    bytes = file_bytes(jpeg);
    const std::size_t sof = bytes.find("\xff\xc0");
    ASSERT_NE(sof, std::string::npos);
    put_big_endian(bytes, sof + 5, 60000, 2);  // height, width
    put_big_endian(bytes, sof + 7, 60000, 2);
    write_bytes(jpeg, bytes);
    EXPECT_NE(expect_raster_error(jpeg).reason.find("60000x60000 JPEG image is more than"), std::string::npos);
}

TEST(Raster, ContentDecidesTheDecoderNotTheExtension) {
    const Raster in = noise(9, 7, 3, 8, 9);
    const fs::path path = temp_path("really_a_png.jpg");
    io::write_raster(path, in, RasterFormat::png);
    EXPECT_EQ(io::read_raster(path).samples, in.samples);
}

TEST(Raster, SixteenBitPngReadsAsFloatWithoutLosingPrecision) {
    Raster in(3, 1, 3, 16);
    in.samples = {0, 1, 2, 32768, 40000, 65535, 257, 65534, 12345};
    const fs::path path = temp_path("deep.png");
    io::write_raster(path, in, RasterFormat::png);
    const io::Image image = io::read_image(path);
    ASSERT_EQ(image.channels, 3);
    for (std::size_t i = 0; i < in.samples.size(); ++i)
        EXPECT_EQ(image.pixels[i], static_cast<float>(in.samples[i]) / 65535.0f) << i;
}

TEST(Raster, FormatByExtension) {
    RasterFormat format = RasterFormat::png;
    EXPECT_TRUE(io::raster_format_by_extension("a.TIFF", format));
    EXPECT_EQ(format, RasterFormat::tiff);
    EXPECT_TRUE(io::raster_format_by_extension("a.Jpeg", format));
    EXPECT_EQ(format, RasterFormat::jpeg);
    EXPECT_TRUE(io::raster_format_by_extension("a.png", format));
    EXPECT_EQ(format, RasterFormat::png);
    EXPECT_FALSE(io::raster_format_by_extension("a.bmp", format));
    EXPECT_FALSE(io::raster_format_by_extension("png", format));
}
