#include "surfscatter/photo/photo_io.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo {

namespace {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

bool is_exr(const std::string& ext) { return ext == ".exr"; }
bool is_opencv_format(const std::string& ext) {
    return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".tif" || ext == ".tiff";
}

Photo read_exr(const std::filesystem::path& path) {
    const io::Image image = io::read_image(path);
    Photo photo;
    photo.bit_depth = 32;
    photo.rgb.create(image.height, image.width, CV_32FC3);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            cv::Vec3f& px = photo.rgb.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) px[c] = image.at(x, y, std::min(c, image.channels - 1));
        }
    return photo;
}

// ---- EXIF: just enough of TIFF to find FocalLength (a RATIONAL in the Exif sub-IFD, sometimes in IFD0).
class TiffReader {
public:
    TiffReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    std::optional<double> focal_length() const {
        if (size_ < 8) return std::nullopt;
        if (data_[0] == 'I' && data_[1] == 'I') little_ = true;
        else if (data_[0] == 'M' && data_[1] == 'M') little_ = false;
        else return std::nullopt;
        const auto ifd0 = u32(4);
        if (!ifd0) return std::nullopt;
        if (auto f = find_rational(*ifd0, 0x920A)) return f;
        const auto exif_ifd = find_long(*ifd0, 0x8769);
        if (!exif_ifd) return std::nullopt;
        return find_rational(*exif_ifd, 0x920A);
    }

private:
    std::optional<std::uint32_t> u16(std::size_t at) const {
        if (at + 2 > size_) return std::nullopt;
        return little_ ? std::uint32_t(data_[at] | data_[at + 1] << 8) : std::uint32_t(data_[at] << 8 | data_[at + 1]);
    }
    std::optional<std::uint32_t> u32(std::size_t at) const {
        const auto lo = u16(little_ ? at : at + 2), hi = u16(little_ ? at + 2 : at);
        if (!lo || !hi) return std::nullopt;
        return *hi << 16 | *lo;
    }
    // Offset of the value field of the entry `tag` in the IFD at `ifd`.
    std::optional<std::size_t> find_entry(std::size_t ifd, std::uint32_t tag) const {
        const auto count = u16(ifd);
        if (!count) return std::nullopt;
        for (std::uint32_t i = 0; i < *count; ++i) {
            const std::size_t entry = ifd + 2 + 12 * std::size_t(i);
            const auto t = u16(entry);
            if (!t) return std::nullopt;
            if (*t == tag) return entry + 8;
        }
        return std::nullopt;
    }
    std::optional<std::uint32_t> find_long(std::size_t ifd, std::uint32_t tag) const {
        const auto value = find_entry(ifd, tag);
        return value ? u32(*value) : std::nullopt;
    }
    std::optional<double> find_rational(std::size_t ifd, std::uint32_t tag) const {
        const auto offset = find_long(ifd, tag);
        if (!offset) return std::nullopt;
        const auto num = u32(*offset), den = u32(*offset + 4);
        if (!num || !den || *den == 0) return std::nullopt;
        return double(*num) / double(*den);
    }

    const std::uint8_t* data_;
    std::size_t size_;
    mutable bool little_ = true;
};

}  // namespace

Encoding encoding_by_name(const std::string& name) {
    if (name == "srgb") return Encoding::Srgb;
    if (name == "linear") return Encoding::Linear;
    fail("unknown sample encoding '{}' (expected srgb or linear)", name);
}

std::optional<double> read_exif_focal_length(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return std::nullopt;
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = lower_extension(path);
    if (ext == ".tif" || ext == ".tiff") return TiffReader(bytes.data(), bytes.size()).focal_length();
    // JPEG: walk the marker segments up to the image data looking for APP1 "Exif\0\0".
    std::size_t at = 2;
    if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
    while (at + 4 <= bytes.size() && bytes[at] == 0xFF) {
        const std::uint8_t marker = bytes[at + 1];
        const std::size_t length = std::size_t(bytes[at + 2]) << 8 | bytes[at + 3];
        if (marker == 0xDA || length < 2 || at + 2 + length > bytes.size()) break;
        const std::uint8_t* segment = bytes.data() + at + 4;
        if (marker == 0xE1 && length >= 8 && std::equal(segment, segment + 6, "Exif\0\0"))
            return TiffReader(segment + 6, length - 8).focal_length();
        at += 2 + length;
    }
    return std::nullopt;
}

Photo read_photo(const std::filesystem::path& path, Encoding encoding) {
    if (!std::filesystem::exists(path)) fail("image '{}' does not exist", path.string());
    const std::string ext = lower_extension(path);
    if (is_exr(ext)) return read_exr(path);
    if (!is_opencv_format(ext))
        fail("image '{}': unsupported type '{}' (expected .png, .jpg, .jpeg, .tif, .tiff or .exr)", path.string(), ext);

    const cv::Mat raw = cv::imread(path.string(), cv::IMREAD_UNCHANGED | cv::IMREAD_IGNORE_ORIENTATION);
    if (raw.empty()) fail("image '{}' could not be decoded", path.string());
    double scale = 0.0;
    Photo photo;
    switch (raw.depth()) {
        case CV_8U: scale = 1.0 / 255.0; photo.bit_depth = 8; break;
        case CV_16U: scale = 1.0 / 65535.0; photo.bit_depth = 16; break;
        default: fail("image '{}': unsupported sample type (expected 8- or 16-bit integers)", path.string());
    }
    cv::Mat bgr;
    switch (raw.channels()) {
        case 1: cv::cvtColor(raw, bgr, cv::COLOR_GRAY2BGR); break;
        case 3: bgr = raw; break;
        case 4: cv::cvtColor(raw, bgr, cv::COLOR_BGRA2BGR); break;
        default: fail("image '{}' has {} channels (expected 1, 3 or 4)", path.string(), raw.channels());
    }
    cv::Mat rgb;
    cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
    rgb.convertTo(rgb, CV_32F, scale);
    photo.rgb = encoding == Encoding::Srgb ? srgb_decode_image(rgb) : rgb;
    photo.focal_length_mm = read_exif_focal_length(path);
    return photo;
}

void write_photo(const std::filesystem::path& path, const cv::Mat& linear_rgb, Encoding encoding) {
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
    if (!is_opencv_format(ext))
        fail("output '{}': unsupported type '{}' (expected .png, .jpg, .jpeg, .tif, .tiff or .exr)", path.string(), ext);
    const cv::Mat encoded = encoding == Encoding::Srgb ? srgb_encode_image(linear_rgb) : linear_rgb;
    cv::Mat bgr;
    cv::cvtColor(encoded, bgr, cv::COLOR_RGB2BGR);
    const bool eight_bit = ext == ".jpg" || ext == ".jpeg";
    cv::Mat out;
    bgr.convertTo(out, eight_bit ? CV_8U : CV_16U, eight_bit ? 255.0 : 65535.0);  // saturating
    std::vector<int> params;
    if (eight_bit) params = {cv::IMWRITE_JPEG_QUALITY, 95};
    bool ok = false;
    try {
        ok = cv::imwrite(path.string(), out, params);
    } catch (const cv::Exception& e) {
        fail("output '{}' could not be written: {}", path.string(), e.what());
    }
    if (!ok) fail("output '{}' could not be written", path.string());
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

}  // namespace surfscatter::photo
