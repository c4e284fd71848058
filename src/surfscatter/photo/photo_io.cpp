#include "surfscatter/photo/photo_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdarg>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <libexif/exif-data.h>
#include <opencv2/imgproc.hpp>
#include <tiffio.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/photo/camera_raw.hpp"
#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo {

using io::lower_extension;

namespace {

bool is_exr(const std::string& ext) { return ext == ".exr"; }
// Extensions of the camera RAW formats LibRaw reads (it recognises a file by its content; this only routes).
bool is_camera_raw(const std::string& ext) {
    static constexpr std::array<std::string_view, 25> kExtensions{
        ".dng", ".cr2", ".cr3", ".crw", ".nef", ".nrw", ".arw", ".srf", ".sr2", ".raf", ".orf", ".rw2", ".rwl",
        ".pef", ".srw", ".3fr", ".fff", ".iiq", ".erf", ".kdc", ".dcr", ".mef", ".mos", ".mrw", ".raw"};
    return std::find(kExtensions.begin(), kExtensions.end(), ext) != kExtensions.end();
}

Photo read_exr(const std::filesystem::path& path) {
    const io::Image image = io::read_image(path);
    Photo photo;
    photo.bit_depth = 32;
    photo.rgb.create(image.height, image.width, CV_32FC3);
    // The one float reader of photographs: a NaN or infinite sample (an EXR may hold them) is refused here, so that
    // undistort, compare and colorcorrect never carry one into their outputs.
    std::size_t bad = 0;
    int first_x = 0, first_y = 0;
    float first = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            cv::Vec3f& px = photo.rgb.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) {
                px[c] = image.at(x, y, std::min(c, image.channels - 1));
                if (!std::isfinite(px[c]) && bad++ == 0) first_x = x, first_y = y, first = px[c];
            }
        }
    if (bad > 0)
        fail("image '{}': {} samples are not finite (the first, at pixel ({}, {}), is {})", path.string(), bad, first_x,
             first_y, first);
    return photo;
}

// ---- EXIF FocalLength (tag 0x920A, a RATIONAL in the Exif IFD): libexif for JPEG, libtiff for TIFF.
std::optional<double> positive(double focal_mm) {
    if (std::isfinite(focal_mm) && focal_mm > 0.0) return focal_mm;
    return std::nullopt;
}

std::optional<double> jpeg_focal_length(const std::filesystem::path& path) {
    const std::unique_ptr<ExifData, void (*)(ExifData*)> exif(exif_data_new_from_file(path.c_str()), &exif_data_unref);
    if (!exif) return std::nullopt;
    const ExifEntry* entry = exif_content_get_entry(exif->ifd[EXIF_IFD_EXIF], EXIF_TAG_FOCAL_LENGTH);
    if (!entry || entry->format != EXIF_FORMAT_RATIONAL || entry->components < 1) return std::nullopt;
    const ExifRational r = exif_get_rational(entry->data, exif_data_get_byte_order(exif.get()));
    if (r.denominator == 0) return std::nullopt;
    return positive(double(r.numerator) / double(r.denominator));
}

// libtiff prints its warnings and errors unless a handler says it dealt with them.
int quiet_tiff_handler(TIFF*, void*, const char*, const char*, va_list) { return 1; }

std::optional<double> tiff_focal_length(const std::filesystem::path& path) {
    TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
    TIFFOpenOptionsSetErrorHandlerExtR(options, quiet_tiff_handler, nullptr);
    TIFFOpenOptionsSetWarningHandlerExtR(options, quiet_tiff_handler, nullptr);
    const std::unique_ptr<TIFF, void (*)(TIFF*)> tiff(TIFFOpenExt(path.c_str(), "r", options), &TIFFClose);
    TIFFOpenOptionsFree(options);
    if (!tiff) return std::nullopt;
    toff_t exif_offset = 0;
    if (!TIFFGetField(tiff.get(), TIFFTAG_EXIFIFD, &exif_offset) || !TIFFReadEXIFDirectory(tiff.get(), exif_offset))
        return std::nullopt;
    // libtiff hands a RATIONAL back as float or double depending on its version's field table: ask it which.
    const TIFFField* field = TIFFFindField(tiff.get(), EXIFTAG_FOCALLENGTH, TIFF_ANY);
    if (!field) return std::nullopt;
    if (TIFFFieldSetGetSize(field) == int(sizeof(double))) {
        double focal = 0.0;
        return TIFFGetField(tiff.get(), EXIFTAG_FOCALLENGTH, &focal) ? positive(focal) : std::nullopt;
    }
    float focal = 0.0f;
    return TIFFGetField(tiff.get(), EXIFTAG_FOCALLENGTH, &focal) ? positive(focal) : std::nullopt;
}

// Decodes a PNG/JPEG/TIFF; a file the decoders cannot read is Error naming it as `role` ("image", "mask").
io::Raster read_raster_as(const std::filesystem::path& path, const char* role) {
    try {
        io::Raster raster = io::read_raster(path);
        io::print_warnings(path, raster);
        return raster;
    } catch (const io::RasterError& e) {
        if (e.truncated) fail("{} '{}' is truncated ({})", role, path.string(), e.reason);
        throw;
    }
}

// An 8- or 16-bit cv::Mat of 1 or 3 channels in R, G, B order, written by extension.
void write_mat(const std::filesystem::path& path, const cv::Mat& samples) {
    io::RasterFormat format;
    if (!io::raster_format_by_extension(path, format))
        fail("output '{}': unsupported type '{}' (expected .png, .jpg, .jpeg, .tif, .tiff or .exr)", path.string(),
             path.extension().string());
    const bool sixteen = samples.depth() == CV_16U;
    io::Raster raster(samples.cols, samples.rows, samples.channels(), sixteen ? 16 : 8);
    const cv::Mat flat = samples.reshape(1, samples.rows);
    for (int y = 0; y < samples.rows; ++y)
        for (int i = 0; i < samples.cols * samples.channels(); ++i)
            raster.samples[static_cast<std::size_t>(y) * flat.cols + i] =
                sixteen ? flat.at<std::uint16_t>(y, i) : flat.at<std::uint8_t>(y, i);
    try {
        io::write_raster(path, raster, format);
    } catch (const Error& e) {
        fail("output '{}' could not be written: {}", path.string(), e.what());
    }
}

}  // namespace

Encoding encoding_by_name(const std::string& name) {
    if (name == "srgb") return Encoding::Srgb;
    if (name == "linear") return Encoding::Linear;
    fail("unknown sample encoding '{}' (expected srgb or linear)", name);
}

std::optional<double> read_exif_focal_length(const std::filesystem::path& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".jpg" || ext == ".jpeg") return jpeg_focal_length(path);
    if (ext == ".tif" || ext == ".tiff") return tiff_focal_length(path);
    return std::nullopt;
}

Photo read_photo(const std::filesystem::path& path, Encoding encoding) {
    if (!std::filesystem::exists(path)) fail("image '{}' does not exist", path.string());
    if (std::filesystem::is_directory(path)) fail("image '{}' is a directory", path.string());
    const std::string ext = lower_extension(path);
    if (is_exr(ext)) return read_exr(path);
    if (is_camera_raw(ext)) {
        if (auto photo = read_camera_raw(path)) return *std::move(photo);
        fail("camera RAW '{}' could not be opened by LibRaw (a format it does not know, or a damaged header)",
             path.string());
    }
    io::RasterFormat format;
    if (!io::raster_format_by_extension(path, format))
        fail("image '{}': unsupported type '{}' (expected .png, .jpg, .jpeg, .tif, .tiff, .exr or camera RAW such as "
             ".dng, .cr2, .nef, .arw)", path.string(), ext);

    io::Raster raster;
    try {
        raster = read_raster_as(path, "image");
    } catch (const io::RasterError& e) {
        // A camera RAW file under an image extension is still read.
        if (auto photo = read_camera_raw(path)) return *std::move(photo);
        fail("image '{}' could not be decoded ({})", path.string(), e.reason);
    }
    Photo photo;
    photo.bit_depth = raster.bit_depth;
    // As OpenCV's convertTo(CV_32F, scale): the product in float.
    const float scale = static_cast<float>(raster.bit_depth == 16 ? 1.0 / 65535.0 : 1.0 / 255.0);
    cv::Mat rgb(raster.height, raster.width, CV_32FC3);
    for (int y = 0; y < raster.height; ++y)
        for (int x = 0; x < raster.width; ++x) {
            cv::Vec3f& px = rgb.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) px[c] = static_cast<float>(raster.at(x, y, raster.channels < 3 ? 0 : c)) * scale;
        }
    photo.rgb = encoding == Encoding::Srgb ? srgb_decode_image(rgb) : rgb;
    photo.encoded = true;
    photo.focal_length_mm = read_exif_focal_length(path);
    return photo;
}

void write_photo(const std::filesystem::path& path, const cv::Mat& linear_rgb, Encoding encoding) {
    // An empty image has no type to assert on (OpenCV's assertion was an "internal error"): bad input, named.
    if (linear_rgb.empty())
        fail("cannot write '{}': the image is empty ({}x{} pixels)", printable(path.string(), kShownPathChars),
             linear_rgb.cols, linear_rgb.rows);
    CV_Assert(linear_rgb.type() == CV_32FC3);
    const std::string ext = lower_extension(path);
    if (is_exr(ext)) {
        io::Image image(linear_rgb.cols, linear_rgb.rows, 3);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                for (int c = 0; c < 3; ++c) image.at(x, y, c) = linear_rgb.at<cv::Vec3f>(y, x)[c];
        io::write_exr(path, image);
        return;
    }
    const cv::Mat encoded = encoding == Encoding::Srgb ? srgb_encode_image(linear_rgb) : linear_rgb;
    io::RasterFormat format;
    const bool eight_bit = io::raster_format_by_extension(path, format) && format == io::RasterFormat::jpeg;
    cv::Mat out;
    encoded.convertTo(out, eight_bit ? CV_8U : CV_16U, eight_bit ? 255.0 : 65535.0);  // saturating, rounded
    write_mat(path, out);
}

void write_display_image(const std::filesystem::path& path, const cv::Mat& bgr8) {
    CV_Assert(bgr8.type() == CV_8UC3);
    cv::Mat rgb;
    cv::cvtColor(bgr8, rgb, cv::COLOR_BGR2RGB);
    write_mat(path, rgb);
}

cv::Mat read_grey8(const std::filesystem::path& path, const char* role) {
    if (!std::filesystem::exists(path)) fail("{} '{}' does not exist", role, path.string());
    io::Raster raster;
    try {
        raster = read_raster_as(path, role);
    } catch (const io::RasterError& e) {
        fail("{} '{}' could not be decoded ({})", role, path.string(), e.reason);
    }
    const int shift = raster.bit_depth == 16 ? 8 : 0;  // the high byte, as OpenCV's IMREAD_GRAYSCALE
    cv::Mat samples(raster.height, raster.width, CV_8UC(raster.channels));
    for (int y = 0; y < raster.height; ++y)
        for (int i = 0; i < raster.width * raster.channels; ++i)
            samples.ptr<std::uint8_t>(y)[i] = static_cast<std::uint8_t>(
                raster.samples[static_cast<std::size_t>(y) * raster.width * raster.channels + i] >> shift);
    if (raster.channels == 1) return samples;
    cv::Mat grey;
    cv::cvtColor(samples, grey, raster.channels == 4 ? cv::COLOR_RGBA2GRAY : cv::COLOR_RGB2GRAY);
    return grey;
}

cv::Mat to_display_bgr8(const cv::Mat& linear_rgb) {
    cv::Mat bgr, out;
    cv::cvtColor(srgb_encode_image(linear_rgb), bgr, cv::COLOR_RGB2BGR);
    bgr.convertTo(out, CV_8U, 255.0);
    return out;
}

cv::Mat to_gray8(const cv::Mat& linear_rgb) {
    cv::Mat gray;
    cv::cvtColor(to_display_bgr8(linear_rgb), gray, cv::COLOR_BGR2GRAY);
    return gray;
}

cv::Mat to_linear_gray(const cv::Mat& linear_rgb) {
    cv::Mat gray;
    cv::cvtColor(linear_rgb, gray, cv::COLOR_RGB2GRAY);
    return gray;
}

}  // namespace surfscatter::photo
