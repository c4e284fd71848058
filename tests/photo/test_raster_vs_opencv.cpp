// The independent check of io/raster.hpp: every real photograph under ../shared/data/realdata and files of every
// PNG/JPEG/TIFF layout OpenCV (and libpng/libjpeg here) can write, decoded by io::read_raster and by OpenCV 4.6's
// imread(IMREAD_UNCHANGED | IMREAD_IGNORE_ORIENTATION), which read_photo used before. The samples must be identical:
// both use the same Debian libpng, libjpeg-turbo and libtiff with the same settings (libjpeg's default islow IDCT
// and fancy upsampling), so even JPEG has no reason to differ by a level.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <opencv2/imgcodecs.hpp>
#include <png.h>

#include "surfscatter/io/raster.hpp"

namespace fs = std::filesystem;
using namespace surfscatter;

namespace {

fs::path temp_path(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / "surfscatter_test_raster_vs_opencv";
    fs::create_directories(dir);
    return dir / name;
}

// Decodes `path` both ways and requires the same size, channels, depth and samples (OpenCV's B, G, R order mapped).
void expect_same_as_opencv(const fs::path& path) {
    SCOPED_TRACE(path.string());
    const cv::Mat mat = cv::imread(path.string(), cv::IMREAD_UNCHANGED | cv::IMREAD_IGNORE_ORIENTATION);
    ASSERT_FALSE(mat.empty());
    const io::Raster raster = io::read_raster(path);
    ASSERT_EQ(raster.width, mat.cols);
    ASSERT_EQ(raster.height, mat.rows);
    ASSERT_EQ(raster.channels, mat.channels());
    ASSERT_EQ(raster.bit_depth, mat.depth() == CV_16U ? 16 : mat.depth() == CV_8U ? 8 : -1);
    const int channels = raster.channels;
    std::size_t differing = 0;
    for (int y = 0; y < mat.rows; ++y)
        for (int x = 0; x < mat.cols; ++x)
            for (int c = 0; c < channels; ++c) {
                const int cv_channel = channels >= 3 && c < 3 ? 2 - c : c;  // B G R (A) -> R G B (A)
                const int opencv = mat.depth() == CV_16U ? mat.ptr<std::uint16_t>(y)[x * channels + cv_channel]
                                                         : mat.ptr<std::uint8_t>(y)[x * channels + cv_channel];
                if (opencv != raster.at(x, y, c)) ++differing;
            }
    EXPECT_EQ(differing, 0u) << "of " << raster.samples.size() << " samples";
}

cv::Mat noise(int rows, int cols, int type, unsigned seed) {
    cv::Mat mat(rows, cols, type);
    cv::RNG rng(seed);
    rng.fill(mat, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
    return mat;
}

cv::Mat smooth_bgr(int rows, int cols) {
    cv::Mat mat(rows, cols, CV_8UC3);
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < cols; ++x)
            mat.at<cv::Vec3b>(y, x) = cv::Vec3b(cv::saturate_cast<uchar>(128 + 100 * std::sin(0.05 * x)),
                                                cv::saturate_cast<uchar>(128 + 90 * std::cos(0.07 * y)),
                                                cv::saturate_cast<uchar>((x * y) % 256));
    return mat;
}

// A palette PNG (with transparency for some entries, optionally Adam7-interlaced) or a grey PNG of 1/2/4 bits
// with a transparent grey: layouts cv::imwrite does not write.
void write_png_by_hand(const fs::path& path, int color_type, int depth, bool transparency, bool interlaced) {
    const int width = 37, height = 23;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, file);
    png_set_IHDR(png, info, width, height, depth, color_type, interlaced ? PNG_INTERLACE_ADAM7 : PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    const int entries = 1 << depth;
    if (color_type == PNG_COLOR_TYPE_PALETTE) {
        std::vector<png_color> palette(static_cast<std::size_t>(entries));
        for (int i = 0; i < entries; ++i)
            palette[static_cast<std::size_t>(i)] = {static_cast<png_byte>(i * 37), static_cast<png_byte>(255 - i * 11),
                                                    static_cast<png_byte>(i * i)};
        png_set_PLTE(png, info, palette.data(), entries);
        if (transparency) {
            std::vector<png_byte> alpha{0, 128, 255};
            png_set_tRNS(png, info, alpha.data(), std::min(entries, 3), nullptr);
        }
    } else if (transparency) {
        png_color_16 grey{};
        grey.gray = 1;
        png_set_tRNS(png, info, nullptr, 0, &grey);
    }
    png_write_info(png, info);
    std::mt19937 rng(static_cast<unsigned>(depth * 10 + color_type));
    const std::size_t row_bytes = (static_cast<std::size_t>(width) * depth + 7) / 8;
    std::vector<std::vector<png_byte>> rows(height, std::vector<png_byte>(row_bytes));
    std::vector<png_bytep> pointers;
    for (auto& row : rows) {
        for (auto& b : row) b = static_cast<png_byte>(rng());
        pointers.push_back(row.data());
    }
    png_write_image(png, pointers.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
}

// A CMYK (Adobe) JPEG written with libjpeg: OpenCV converts it to BGR with its own formula.
void write_cmyk_jpeg(const fs::path& path) {
    const int width = 40, height = 24;
    std::FILE* file = std::fopen(path.c_str(), "wb");
    ASSERT_NE(file, nullptr);
    jpeg_compress_struct info;
    jpeg_error_mgr errors;
    info.err = jpeg_std_error(&errors);
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, file);
    info.image_width = width;
    info.image_height = height;
    info.input_components = 4;
    info.in_color_space = JCS_CMYK;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, 90, TRUE);
    jpeg_start_compress(&info, TRUE);
    std::vector<JSAMPLE> row(static_cast<std::size_t>(width) * 4);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x)
            for (int c = 0; c < 4; ++c) row[static_cast<std::size_t>(x) * 4 + c] = static_cast<JSAMPLE>((x * 6 + y * 9 + c * 60) % 256);
        JSAMPROW pointer = row.data();
        jpeg_write_scanlines(&info, &pointer, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    std::fclose(file);
}

}  // namespace

TEST(RasterVsOpenCv, EveryRealPhotographDecodesToTheSameSamples) {
    const fs::path root = fs::path(SURFSCATTER_SHARED_DATA) / "realdata";
    ASSERT_TRUE(fs::is_directory(root)) << root;
    int images = 0;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        io::RasterFormat format;
        if (!entry.is_regular_file() || !io::raster_format_by_extension(entry.path(), format)) continue;
        expect_same_as_opencv(entry.path());
        ++images;
    }
    EXPECT_GE(images, 2);  // the two ArUco tutorial photographs (README there)
}

TEST(RasterVsOpenCv, PngAndTiffOfEveryDepthAndChannelCount) {
    int seed = 0;
    for (const char* ext : {".png", ".tif"})
        for (int depth : {CV_8U, CV_16U})
            for (int channels : {1, 3, 4}) {
                const fs::path path = temp_path(std::string("noise") + ext);
                ASSERT_TRUE(cv::imwrite(path.string(), noise(31, 45, CV_MAKETYPE(depth, channels), ++seed)));
                expect_same_as_opencv(path);
            }
    // TIFF compressions: none, LZW, deflate, PackBits.
    for (int compression : {1, 5, 8, 32773}) {
        const fs::path path = temp_path("compressed.tif");
        ASSERT_TRUE(cv::imwrite(path.string(), noise(30, 50, CV_16UC3, 77), {cv::IMWRITE_TIFF_COMPRESSION, compression}));
        expect_same_as_opencv(path);
    }
    const fs::path bilevel = temp_path("bilevel.png");
    ASSERT_TRUE(cv::imwrite(bilevel.string(), noise(20, 33, CV_8UC1, 5) > 128, {cv::IMWRITE_PNG_BILEVEL, 1}));
    expect_same_as_opencv(bilevel);
}

TEST(RasterVsOpenCv, PalettesTransparencyAndInterlacedPng) {
    for (int depth : {1, 2, 4, 8})
        for (bool transparency : {false, true}) {
            const fs::path path = temp_path("palette.png");
            write_png_by_hand(path, PNG_COLOR_TYPE_PALETTE, depth, transparency, depth == 8);
            expect_same_as_opencv(path);
            write_png_by_hand(path, PNG_COLOR_TYPE_GRAY, depth, transparency, depth == 4);
            expect_same_as_opencv(path);
        }
}

TEST(RasterVsOpenCv, JpegGreyColourProgressiveAndCmyk) {
    const fs::path path = temp_path("photo.jpg");
    ASSERT_TRUE(cv::imwrite(path.string(), smooth_bgr(61, 83), {cv::IMWRITE_JPEG_QUALITY, 90}));
    expect_same_as_opencv(path);
    ASSERT_TRUE(cv::imwrite(path.string(), smooth_bgr(61, 83), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
    expect_same_as_opencv(path);
    cv::Mat grey;
    cv::extractChannel(smooth_bgr(50, 40), grey, 1);
    ASSERT_TRUE(cv::imwrite(path.string(), grey));
    expect_same_as_opencv(path);
    write_cmyk_jpeg(path);
    expect_same_as_opencv(path);
}

TEST(RasterVsOpenCv, WrittenFilesDecodeToWhatOpenCvsWriterGave) {
    // write_photo used cv::imwrite: 16-bit PNG/TIFF, JPEG at quality 95 (libjpeg's defaults otherwise, 4:2:0). The
    // same samples written both ways decode to the same samples (JPEG included: the same encoder and settings).
    const cv::Mat bgr16 = noise(27, 35, CV_16UC3, 31);
    const cv::Mat bgr8 = smooth_bgr(27, 35);
    for (const auto& [ext, format] : {std::pair{".png", io::RasterFormat::png}, std::pair{".tif", io::RasterFormat::tiff},
                                      std::pair{".jpg", io::RasterFormat::jpeg}}) {
        const cv::Mat& bgr = format == io::RasterFormat::jpeg ? bgr8 : bgr16;
        io::Raster raster(bgr.cols, bgr.rows, 3, bgr.depth() == CV_16U ? 16 : 8);
        for (int y = 0; y < bgr.rows; ++y)
            for (int x = 0; x < bgr.cols; ++x)
                for (int c = 0; c < 3; ++c)
                    raster.at(x, y, c) = bgr.depth() == CV_16U ? bgr.at<cv::Vec3w>(y, x)[2 - c] : bgr.at<cv::Vec3b>(y, x)[2 - c];
        const fs::path ours = temp_path(std::string("ours") + ext), theirs = temp_path(std::string("theirs") + ext);
        io::write_raster(ours, raster, format, 95);
        ASSERT_TRUE(cv::imwrite(theirs.string(), bgr, {cv::IMWRITE_JPEG_QUALITY, 95}));
        EXPECT_EQ(io::read_raster(ours).samples, io::read_raster(theirs).samples) << ext;
    }
}
