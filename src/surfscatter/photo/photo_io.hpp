#pragma once
// Reading and writing photographs for the pipeline. In memory a photograph is a CV_32FC3 cv::Mat with channels in
// R, G, B order (not OpenCV's usual B, G, R) holding LINEAR values, 1 = the file's full scale.
//
// Files: JPEG and 8/16-bit PNG/TIFF through surfscatter::io's raster.hpp (libjpeg, libpng, libtiff; sRGB-encoded
// unless told otherwise), OpenEXR through surfscatter::io (linear), camera RAW (.dng, .cr2, .nef, .arw, .raf, ...)
// through LibRaw as linear sRGB (camera_raw.hpp states the processing). docs/PHOTO.md, "Images".
#include <filesystem>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

namespace surfscatter::photo {

// How the integer samples of a PNG/JPEG/TIFF are encoded. EXR and camera RAW are always linear.
enum class Encoding { Srgb, Linear };
Encoding encoding_by_name(const std::string& name);  // "srgb" | "linear"; throws Error otherwise

struct Photo {
    cv::Mat rgb;                             // CV_32FC3, linear, R G B
    int bit_depth = 8;                       // of the decoded samples (32 for EXR, 16 for camera RAW)
    bool encoded = false;                    // integer PNG/JPEG/TIFF samples, read as the Encoding asked (EXR and
                                             // camera RAW are linear whatever it says)
    std::optional<double> focal_length_mm;   // EXIF FocalLength (JPEG, TIFF, camera RAW), when present
};

// Throws Error naming the file when it is missing, a directory, unreadable, truncated, of an unknown type or not
// 1/3/4 channels. A file with an image extension that the decoders cannot read is offered to LibRaw before giving
// up. The decoders' messages become the error (a truncated file is "truncated"), or, for a file that decodes with
// warnings, one "surfscatter: warning:" line naming the file. Grey is expanded to RGB, alpha dropped.
Photo read_photo(const std::filesystem::path& path, Encoding encoding = Encoding::Srgb);

// Writes by extension: .png (16-bit), .tif/.tiff (16-bit), .jpg/.jpeg (8-bit), all sRGB-encoded unless
// `encoding` is Linear; .exr as linear 32-bit float. Values outside [0, 1] are clipped for integer formats.
void write_photo(const std::filesystem::path& path, const cv::Mat& linear_rgb, Encoding encoding = Encoding::Srgb);

// Writes an 8-bit B, G, R image (a comparison sheet) as PNG, JPEG (quality 95) or TIFF by extension.
void write_display_image(const std::filesystem::path& path, const cv::Mat& bgr8);

// An image file (PNG, JPEG, TIFF) as 8-bit grey, as OpenCV's imread(IMREAD_GRAYSCALE) would give for grey files;
// 16-bit samples keep their high byte, colour is converted with cv::COLOR_RGB2GRAY. `role` names the file in errors.
cv::Mat read_grey8(const std::filesystem::path& path, const char* role);

// 8-bit B, G, R sRGB-encoded view of a linear image (for detectors and for sheets), clipped to [0, 1].
cv::Mat to_display_bgr8(const cv::Mat& linear_rgb);
// 8-bit grey (sRGB-encoded luma) for marker and board detection.
cv::Mat to_gray8(const cv::Mat& linear_rgb);
// Linear luminance (CV_32FC1) of a CV_32FC3 linear RGB image: where sub-pixel corners and edges are measured.
cv::Mat to_linear_gray(const cv::Mat& linear_rgb);

// EXIF FocalLength (tag 0x920A) in millimetres from a JPEG's APP1 segment (libexif) or a TIFF's Exif IFD
// (libtiff), if present and positive. Camera RAW files get theirs from LibRaw in read_photo.
std::optional<double> read_exif_focal_length(const std::filesystem::path& path);

}  // namespace surfscatter::photo
