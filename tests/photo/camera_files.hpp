#pragma once
// Camera files written byte by byte for the photo tests, so that no RAW or EXIF sample is committed: a little-endian
// TIFF writer, a minimal DNG (one 16-bit RGGB CFA image in IFD0) of a known linear scene, and JPEG/TIFF
// photographs carrying an EXIF FocalLength. Header-only: tests/photo and tests/cli use it.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo::camera_files {

// One TIFF image file directory. Entries may be given in any order (written sorted by tag, as TIFF requires).
class TiffIfd {
public:
    TiffIfd& ascii(std::uint16_t tag, const std::string& text) {
        std::vector<std::uint8_t> value(text.begin(), text.end());
        value.push_back(0);
        return add(tag, kAscii, std::uint32_t(value.size()), std::move(value));
    }
    TiffIfd& bytes(std::uint16_t tag, const std::vector<std::uint8_t>& values) {
        return add(tag, kByte, std::uint32_t(values.size()), values);
    }
    TiffIfd& shorts(std::uint16_t tag, const std::vector<std::uint16_t>& values) {
        std::vector<std::uint8_t> value;
        for (std::uint16_t v : values) put(value, v, 2);
        return add(tag, kShort, std::uint32_t(values.size()), std::move(value));
    }
    TiffIfd& longs(std::uint16_t tag, const std::vector<std::uint32_t>& values) {
        std::vector<std::uint8_t> value;
        for (std::uint32_t v : values) put(value, v, 4);
        return add(tag, kLong, std::uint32_t(values.size()), std::move(value));
    }
    // RATIONAL (unsigned) or SRATIONAL values as round(v * denominator) / denominator.
    TiffIfd& rationals(std::uint16_t tag, const std::vector<double>& values, std::uint32_t denominator,
                       bool is_signed = false) {
        std::vector<std::uint8_t> value;
        for (double v : values) {
            put(value, std::uint32_t(std::int32_t(std::lround(v * denominator))), 4);
            put(value, denominator, 4);
        }
        return add(tag, is_signed ? kSrational : kRational, std::uint32_t(values.size()), std::move(value));
    }
    // A LONG entry holding the offset of `ifd`, written after this one (e.g. the Exif IFD, tag 0x8769).
    TiffIfd& sub_ifd(std::uint16_t tag, TiffIfd ifd) {
        add(tag, kLong, 1, {});
        entries_.back().sub = std::make_shared<TiffIfd>(std::move(ifd));
        return *this;
    }
    // StripOffsets (273) and StripByteCounts (279) of one strip holding `data`.
    TiffIfd& strip(std::vector<std::uint8_t> data) {
        longs(279, {std::uint32_t(data.size())});
        add(273, kLong, 1, std::move(data));
        entries_.back().is_strip = true;
        return *this;
    }

    // Appends the IFD (then its out-of-line values, strips and sub-IFDs) to `out`; returns its offset.
    std::uint32_t write(std::vector<std::uint8_t>& out) const {
        std::vector<Entry> sorted = entries_;
        std::stable_sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
        align(out);
        const std::size_t at = out.size();
        put(out, sorted.size(), 2);
        out.resize(out.size() + 12 * sorted.size() + 4, 0);  // the entries, then "no next IFD"
        for (std::size_t i = 0; i < sorted.size(); ++i) {
            const Entry& e = sorted[i];
            const std::size_t entry = at + 2 + 12 * i;
            patch(out, entry, e.tag, 2);
            patch(out, entry + 2, e.type, 2);
            patch(out, entry + 4, e.count, 4);
            if (e.sub) {
                patch(out, entry + 8, e.sub->write(out), 4);
            } else if (e.is_strip || e.value.size() > 4) {
                align(out);
                patch(out, entry + 8, out.size(), 4);
                out.insert(out.end(), e.value.begin(), e.value.end());
            } else {
                std::copy(e.value.begin(), e.value.end(), out.begin() + std::ptrdiff_t(entry + 8));
            }
        }
        return std::uint32_t(at);
    }

private:
    enum Type : std::uint16_t { kByte = 1, kAscii = 2, kShort = 3, kLong = 4, kRational = 5, kSrational = 10 };
    struct Entry {
        std::uint16_t tag, type;
        std::uint32_t count;
        std::vector<std::uint8_t> value;
        std::shared_ptr<const TiffIfd> sub;
        bool is_strip = false;
    };

    TiffIfd& add(std::uint16_t tag, std::uint16_t type, std::uint32_t count, std::vector<std::uint8_t> value) {
        entries_.push_back({tag, type, count, std::move(value), nullptr, false});
        return *this;
    }
    static void put(std::vector<std::uint8_t>& out, std::uint64_t v, int size) {
        for (int i = 0; i < size; ++i) out.push_back(std::uint8_t(v >> (8 * i)));
    }
    static void patch(std::vector<std::uint8_t>& out, std::size_t at, std::uint64_t v, int size) {
        for (int i = 0; i < size; ++i) out[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    }
    static void align(std::vector<std::uint8_t>& out) {
        if (out.size() % 2) out.push_back(0);
    }

    std::vector<Entry> entries_;
};

// A little-endian TIFF stream whose first IFD is `ifd0`.
inline std::vector<std::uint8_t> tiff_bytes(const TiffIfd& ifd0) {
    std::vector<std::uint8_t> out{'I', 'I', 42, 0, 0, 0, 0, 0};
    const std::uint32_t offset = ifd0.write(out);
    for (int i = 0; i < 4; ++i) out[4 + std::size_t(i)] = std::uint8_t(offset >> (8 * i));
    return out;
}

// An Exif IFD with FocalLength (0x920A) in hundredths of a millimetre.
inline TiffIfd exif_ifd(double focal_length_mm) { return TiffIfd().rationals(0x920A, {focal_length_mm}, 100); }

inline void write_file(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// A simulated camera for DNG files: its RGB response to linear sRGB light is `response` (camera = response * rgb),
// whose rows sum to the as-shot neutral (the camera's reading of white, largest component 1); raw samples are
// black + (white - black) * camera, 16-bit, RGGB.
struct DngCamera {
    cv::Matx33d response;
    std::uint16_t black = 1024;
    std::uint16_t white = 60000;
    std::optional<double> focal_length_mm;
};

// The camera of the RAW tests: cross-talk between the channels and a white that reads (0.52, 1, 0.71).
inline DngCamera test_camera() {
    const cv::Matx33d mix(0.78, 0.17, 0.05, 0.08, 0.84, 0.08, 0.03, 0.19, 0.78);  // rows sum to 1
    return {cv::Matx33d::diag({0.52, 1.0, 0.71}) * mix, 1024, 60000, std::nullopt};
}

// The camera's RGGB mosaic (CV_16UC1) of a linear sRGB scene (CV_32FC3, R G B), clipped at the white level.
inline cv::Mat bayer_mosaic(const cv::Mat& linear_rgb, const DngCamera& camera) {
    cv::Mat raw(linear_rgb.size(), CV_16UC1);
    for (int y = 0; y < raw.rows; ++y)
        for (int x = 0; x < raw.cols; ++x) {
            const int c = (y % 2 == 0) ? (x % 2 == 0 ? 0 : 1) : (x % 2 == 0 ? 1 : 2);
            const cv::Vec3f s = linear_rgb.at<cv::Vec3f>(y, x);
            const cv::Vec3d camera_rgb = camera.response * cv::Vec3d(s[0], s[1], s[2]);
            const double range = double(camera.white) - camera.black;
            raw.at<std::uint16_t>(y, x) = std::uint16_t(
                std::lround(camera.black + range * std::clamp(camera_rgb[c], 0.0, 1.0)));
        }
    return raw;
}

// A minimal DNG 1.4 of `mosaic` (CV_16UC1, RGGB): the raw image in IFD0 with its black and white levels,
// ColorMatrix1 (XYZ -> camera = response * (XYZ -> linear sRGB), D65), AsShotNeutral (response * white) and,
// if given, FocalLength in the Exif IFD.
inline std::vector<std::uint8_t> dng_bytes(const cv::Mat& mosaic, const DngCamera& camera) {
    CV_Assert(mosaic.type() == CV_16UC1);
    cv::Matx33d xyz_to_srgb;
    for (int j = 0; j < 3; ++j) {
        Vec3d unit{0.0, 0.0, 0.0};
        unit[std::size_t(j)] = 1.0;
        const Vec3d column = xyz_to_linear_srgb(unit);
        for (int i = 0; i < 3; ++i) xyz_to_srgb(i, j) = column[std::size_t(i)];
    }
    const cv::Matx33d color_matrix = camera.response * xyz_to_srgb;
    const cv::Vec3d neutral = camera.response * cv::Vec3d(1.0, 1.0, 1.0);

    std::vector<std::uint8_t> pixels(mosaic.total() * 2);
    for (int y = 0; y < mosaic.rows; ++y)
        for (int x = 0; x < mosaic.cols; ++x) {
            const std::uint16_t v = mosaic.at<std::uint16_t>(y, x);
            const std::size_t at = 2 * (std::size_t(y) * std::size_t(mosaic.cols) + std::size_t(x));
            pixels[at] = std::uint8_t(v & 0xFF);
            pixels[at + 1] = std::uint8_t(v >> 8);
        }
    TiffIfd ifd;
    ifd.longs(254, {0})                                                     // NewSubFileType: main image
        .longs(256, {std::uint32_t(mosaic.cols)})                           // ImageWidth
        .longs(257, {std::uint32_t(mosaic.rows)})                           // ImageLength
        .shorts(258, {16})                                                  // BitsPerSample
        .shorts(259, {1})                                                   // Compression: none
        .shorts(262, {32803})                                               // PhotometricInterpretation: CFA
        .ascii(271, "Surfscatter")                                          // Make
        .ascii(272, "Test Camera")                                          // Model
        .shorts(277, {1})                                                   // SamplesPerPixel
        .longs(278, {std::uint32_t(mosaic.rows)})                           // RowsPerStrip
        .shorts(284, {1})                                                   // PlanarConfiguration
        .shorts(33421, {2, 2})                                              // CFARepeatPatternDim
        .bytes(33422, {0, 1, 1, 2})                                         // CFAPattern: R G / G B
        .bytes(50706, {1, 4, 0, 0})                                         // DNGVersion
        .ascii(50708, "Surfscatter Test Camera")                            // UniqueCameraModel
        .longs(50714, {camera.black})                                       // BlackLevel
        .longs(50717, {camera.white})                                       // WhiteLevel
        .rationals(50721,                                                   // ColorMatrix1
                   {color_matrix(0, 0), color_matrix(0, 1), color_matrix(0, 2), color_matrix(1, 0),
                    color_matrix(1, 1), color_matrix(1, 2), color_matrix(2, 0), color_matrix(2, 1),
                    color_matrix(2, 2)},
                   10000, true)
        .rationals(50728, {neutral[0], neutral[1], neutral[2]}, 10000)      // AsShotNeutral
        .shorts(50778, {21})                                                // CalibrationIlluminant1: D65
        .strip(std::move(pixels));
    if (camera.focal_length_mm) ifd.sub_ifd(0x8769, exif_ifd(*camera.focal_length_mm));
    return tiff_bytes(ifd);
}

// The JPEG encoding of `bgr8` (OpenCV, no metadata) with an APP1 "Exif" segment holding FocalLength inserted
// after the start-of-image marker, as cameras write it.
inline std::vector<std::uint8_t> jpeg_with_focal_length(const cv::Mat& bgr8, double focal_length_mm) {
    std::vector<std::uint8_t> jpeg;
    CV_Assert(cv::imencode(".jpg", bgr8, jpeg));
    std::vector<std::uint8_t> app1{'E', 'x', 'i', 'f', 0, 0};
    const auto tiff = tiff_bytes(TiffIfd().sub_ifd(0x8769, exif_ifd(focal_length_mm)));
    app1.insert(app1.end(), tiff.begin(), tiff.end());
    const std::size_t length = app1.size() + 2;
    std::vector<std::uint8_t> segment{0xFF, 0xE1, std::uint8_t(length >> 8), std::uint8_t(length & 0xFF)};
    segment.insert(segment.end(), app1.begin(), app1.end());
    jpeg.insert(jpeg.begin() + 2, segment.begin(), segment.end());
    return jpeg;
}

// An uncompressed 16-bit RGB TIFF of `rgb16` (CV_16UC3 in R G B order) with FocalLength in its Exif IFD.
inline std::vector<std::uint8_t> tiff_with_focal_length(const cv::Mat& rgb16, double focal_length_mm) {
    CV_Assert(rgb16.type() == CV_16UC3 && rgb16.isContinuous());
    std::vector<std::uint8_t> pixels(rgb16.total() * 6);
    const auto* samples = rgb16.ptr<std::uint16_t>();
    for (std::size_t i = 0; i < rgb16.total() * 3; ++i) {
        pixels[2 * i] = std::uint8_t(samples[i] & 0xFF);
        pixels[2 * i + 1] = std::uint8_t(samples[i] >> 8);
    }
    TiffIfd ifd;
    ifd.longs(256, {std::uint32_t(rgb16.cols)})
        .longs(257, {std::uint32_t(rgb16.rows)})
        .shorts(258, {16, 16, 16})
        .shorts(259, {1})
        .shorts(262, {2})  // RGB
        .shorts(277, {3})
        .longs(278, {std::uint32_t(rgb16.rows)})
        .shorts(284, {1})
        .strip(std::move(pixels))
        .sub_ifd(0x8769, exif_ifd(focal_length_mm));
    return tiff_bytes(ifd);
}

}  // namespace surfscatter::photo::camera_files
