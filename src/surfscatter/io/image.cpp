#include "surfscatter/io/image.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <Imath/half.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/io/raster.hpp"

namespace surfscatter::io {

Image::Image(int width_, int height_, int channels_, float fill) : width(width_), height(height_), channels(channels_) {
    if (width_ <= 0 || height_ <= 0) fail("image size must be positive, got {}x{}", width_, height_);
    if (channels_ < 1 || channels_ > 4) fail("image must have 1 to 4 channels, got {}", channels_);
    require_image_memory(width_, height_, 4.0 * channels_, "an image");
    pixels.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * static_cast<std::size_t>(channels_),
                  fill);
}

namespace {

void check_writable(const std::filesystem::path& path, const Image& image) {
    if (image.empty() || image.width <= 0 || image.height <= 0)
        fail("cannot write an empty image to {}", path.string());
    if (image.channels < 1 || image.channels > 4)
        fail("cannot write {}: an image must have 1 to 4 channels, got {}", path.string(), image.channels);
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
        fail("cannot write {}: pixel buffer size does not match {}x{}x{}", path.string(), image.width, image.height,
             image.channels);
}

std::uint8_t to_byte(float v) {
    if (!(v > 0.0f)) return 0;  // also maps NaN to 0
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(v * 255.0f + 0.5f);
}

// PNG and JPEG through io/raster.hpp: the stored 8- or 16-bit samples scaled to [0, 1], grey expanded to RGB.
Image read_raster_image(const std::filesystem::path& path) {
    const Raster raster = read_raster(path);
    print_warnings(path, raster);
    const int channels = raster.channels == 4 ? 4 : 3;
    Image image(raster.width, raster.height, channels);
    const float scale = raster.bit_depth == 16 ? 65535.0f : 255.0f;
    const std::size_t pixels = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.height);
    for (std::size_t p = 0; p < pixels; ++p)
        for (int c = 0; c < channels; ++c)
            image.pixels[p * channels + c] =
                static_cast<float>(raster.samples[p * raster.channels + std::min(c, raster.channels - 1)]) / scale;
    return image;
}

Raster to_raster8(const Image& image) {
    Raster raster(image.width, image.height, image.channels, 8);
    std::transform(image.pixels.begin(), image.pixels.end(), raster.samples.begin(), to_byte);
    return raster;
}

// ---- OpenEXR ----

Image read_exr(const std::filesystem::path& path) {
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i window = file.header().dataWindow();
        const int width = window.max.x - window.min.x + 1;
        const int height = window.max.y - window.min.y + 1;
        const Imf::ChannelList& list = file.header().channels();
        const bool rgb = list.findChannel("R") && list.findChannel("G") && list.findChannel("B");
        const bool grey = !rgb && list.findChannel("Y");
        if (!rgb && !grey) fail("cannot read EXR {}: it has neither R, G, B nor Y channels", path.string());
        const bool alpha = list.findChannel("A") != nullptr;
        Image image(width, height, alpha ? 4 : 3);
        const std::size_t x_stride = sizeof(float) * image.channels;
        const std::size_t y_stride = x_stride * width;
        // OpenEXR addresses the buffer with absolute data-window coordinates.
        char* base = reinterpret_cast<char*>(image.pixels.data()) -
                     (static_cast<std::ptrdiff_t>(window.min.x) * x_stride +
                      static_cast<std::ptrdiff_t>(window.min.y) * y_stride);
        Imf::FrameBuffer frame;
        const char* names[3] = {"R", "G", "B"};
        // A frame buffer holds one slice per channel name: a Y-only file fills channel 0, copied to G and B below.
        for (int c = 0; c < (grey ? 1 : 3); ++c)
            frame.insert(grey ? "Y" : names[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride, 1, 1, 0.0));
        if (alpha) frame.insert("A", Imf::Slice(Imf::FLOAT, base + 3 * sizeof(float), x_stride, y_stride, 1, 1, 1.0));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        if (grey)
            for (int y = 0; y < height; ++y)
                for (int x = 0; x < width; ++x) image.at(x, y, 1) = image.at(x, y, 2) = image.at(x, y, 0);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail("cannot read EXR {}: {}", path.string(), e.what());
    }
}

// ---- Radiance RGBE (.hdr) ----
// Written here (about 80 lines): no Debian library in the dependency set reads it short of OpenCV, which the io
// module does not link. Format: Greg Ward, "Real Pixels", Graphics Gems II (1991), and the Radiance file format notes.

// Largest .hdr file and side read (docs/RELIABILITY.md): 1 GiB is a 16384 x 16384 image without run-length encoding.
constexpr std::uint64_t kMaxHdrBytes = std::uint64_t{1} << 30;
constexpr double kMaxHdrSide = 65536;

Image read_hdr(const std::filesystem::path& path) {
    const std::string name = path.string();
    const std::string bytes = read_input_file(path, "HDR image", kMaxHdrBytes);
    std::string_view rest(bytes);
    const auto next_line = [&] {
        const std::size_t end = rest.find('\n');
        if (end == std::string_view::npos) fail("{}: the HDR header ends early", name);
        const std::string_view line = rest.substr(0, end);
        rest.remove_prefix(end + 1);
        return line;
    };
    std::string_view line = next_line();
    if (line.rfind("#?RADIANCE", 0) != 0 && line.rfind("#?RGBE", 0) != 0)
        fail("{}: not a Radiance HDR file (missing #?RADIANCE)", name);
    double exposure = 1;
    while (!(line = next_line()).empty()) {
        if (line.rfind("FORMAT=", 0) == 0 && line != "FORMAT=32-bit_rle_rgbe")
            fail("{}: unsupported HDR pixel format '{}' (32-bit_rle_rgbe only)", name, printable(line.substr(7)));
        if (line.rfind("EXPOSURE=", 0) == 0) {
            const auto e = to_double(line.substr(9));
            if (!e || !(*e > 0) || !std::isfinite(*e))
                fail("{}: HDR EXPOSURE '{}' is not a positive number", name, printable(line.substr(9)));
            exposure *= *e;
            if (!(exposure > 0) || !std::isfinite(exposure))
                fail("{}: the HDR EXPOSURE lines multiply to {}, outside the double range", name, exposure);
        }
    }
    // The resolution line: "-Y <height> +X <width>", the only orientation read.
    line = next_line();
    std::istringstream words{std::string(line)};
    std::string y_axis, height_text, x_axis, width_text, extra;
    words >> y_axis >> height_text >> x_axis >> width_text;
    const auto height_value = to_double(height_text), width_value = to_double(width_text);
    const auto side = [](std::optional<double> v) { return v && *v >= 1 && *v <= kMaxHdrSide && *v == std::floor(*v); };
    if (y_axis != "-Y" || x_axis != "+X" || (words >> extra) || !side(height_value) || !side(width_value))
        fail("{}: unsupported HDR resolution line '{}' (only the standard '-Y height +X width', sides 1 to {})", name,
             printable(line), kMaxHdrSide);
    const int width = static_cast<int>(*width_value), height = static_cast<int>(*height_value);
    // Fewest bytes a scanline can take (run-length encoded: 4 bytes of header, then runs of up to 127 pixels in two
    // bytes for each of 4 components): no header may make this allocate what the file cannot fill.
    const bool rle_possible = width >= 8 && width < 32768;
    const std::uint64_t scanline_bytes =
        rle_possible ? 4 + 8 * ((static_cast<std::uint64_t>(width) + 126) / 127) : 4 * static_cast<std::uint64_t>(width);
    if (static_cast<std::uint64_t>(height) * scanline_bytes > rest.size())
        fail("{}: a {}x{} HDR image needs at least {} bytes of pixel data, the file holds {}", name, width, height,
             static_cast<std::uint64_t>(height) * scanline_bytes, rest.size());
    Image image(width, height, 3);
    std::vector<std::uint8_t> scanline(static_cast<std::size_t>(width) * 4);
    std::size_t pos = 0;
    auto read_byte = [&]() {
        if (pos == rest.size()) fail("{}: HDR data ends early", name);
        return static_cast<std::uint8_t>(rest[pos++]);
    };
    for (int y = 0; y < height; ++y) {
        const std::uint8_t b0 = read_byte(), b1 = read_byte(), b2 = read_byte(), b3 = read_byte();
        const bool rle = rle_possible && b0 == 2 && b1 == 2 && (b2 & 0x80) == 0;
        if (rle) {
            if (((b2 << 8) | b3) != width) fail("{}: HDR scanline {} has the wrong length", name, y);
            for (int c = 0; c < 4; ++c)
                for (int x = 0; x < width;) {
                    int count = read_byte();
                    const bool run = count > 128;
                    if (run) count -= 128;
                    if (count == 0 || x + count > width) fail("{}: bad HDR run-length data in scanline {}", name, y);
                    const std::uint8_t value = run ? read_byte() : 0;
                    for (int k = 0; k < count; ++k, ++x)
                        scanline[static_cast<std::size_t>(x) * 4 + static_cast<std::size_t>(c)] = run ? value : read_byte();
                }
        } else {
            if (b0 == 1 && b1 == 1 && b2 == 1) fail("{}: old-style HDR run-length encoding is not supported", name);
            scanline[0] = b0, scanline[1] = b1, scanline[2] = b2, scanline[3] = b3;
            for (std::size_t i = 4; i < scanline.size(); ++i) scanline[i] = read_byte();
        }
        for (int x = 0; x < width; ++x) {
            const std::uint8_t* p = &scanline[static_cast<std::size_t>(x) * 4];
            const double scale = p[3] == 0 ? 0.0 : std::ldexp(1.0, p[3] - 136) / exposure;
            for (int c = 0; c < 3; ++c) {
                const double value = p[c] == 0 ? 0.0 : p[c] * scale;
                if (!(value <= std::numeric_limits<float>::max()))
                    fail("{}: pixel ({}, {}) is {} after dividing by the EXPOSURE {}: beyond the float range", name, x,
                         y, value, exposure);
                image.at(x, y, c) = static_cast<float>(value);
            }
        }
    }
    return image;
}

}  // namespace

Image read_image(const std::filesystem::path& path) {
    require_readable_file(path, "image file");
    const std::string ext = lower_extension(path);
    if (ext == ".png" || ext == ".jpg" || ext == ".jpeg") return read_raster_image(path);
    if (ext == ".exr") return read_exr(path);
    if (ext == ".hdr") return read_hdr(path);
    fail("unsupported image format '{}' for {} (expected .png, .jpg, .jpeg, .exr or .hdr)", ext, path.string());
}

void write_png(const std::filesystem::path& path, const Image& image) {
    check_writable(path, image);
    write_raster(path, to_raster8(image), RasterFormat::png);
}

void write_jpeg(const std::filesystem::path& path, const Image& image, int quality) {
    check_writable(path, image);
    write_raster(path, to_raster8(image), RasterFormat::jpeg, std::clamp(quality, 1, 100));
}

void write_exr(const std::filesystem::path& path, const Image& image) {
    static const std::vector<std::string> names[4] = {{"Y"}, {"Y", "A"}, {"R", "G", "B"}, {"R", "G", "B", "A"}};
    check_writable(path, image);
    write_exr(path, image, names[image.channels - 1], ExrPixelType::float32);
}

void write_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& channels,
               ExrPixelType type) {
    check_writable(path, image);
    if (channels.size() != static_cast<std::size_t>(image.channels))
        fail("cannot write EXR {}: {} channel names for {} channels", path.string(), channels.size(), image.channels);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const Imf::PixelType pixel_type = type == ExrPixelType::half ? Imf::HALF : Imf::FLOAT;
        for (const std::string& name : channels) header.channels().insert(name, Imf::Channel(pixel_type));
        // Under a temporary name, renamed into place when whole (core/output_files.hpp).
        OutputFiles files;
        files.output(path, "output");
        files.write_with(path, [&](const std::filesystem::path& tmp) {
            Imf::OutputFile file(tmp.c_str(), header);
            Imf::FrameBuffer frame;
            const std::size_t c_count = static_cast<std::size_t>(image.channels);
            std::vector<Imath::half> halves;
            char* base = nullptr;
            std::size_t sample_size = sizeof(float);
            if (type == ExrPixelType::half) {
                halves.assign(image.pixels.begin(), image.pixels.end());
                base = reinterpret_cast<char*>(halves.data());
                sample_size = sizeof(Imath::half);
            } else {
                base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
            }
            const std::size_t x_stride = sample_size * c_count;
            const std::size_t y_stride = x_stride * static_cast<std::size_t>(image.width);
            for (std::size_t c = 0; c < c_count; ++c)
                frame.insert(channels[c], Imf::Slice(pixel_type, base + c * sample_size, x_stride, y_stride));
            file.setFrameBuffer(frame);
            file.writePixels(image.height);
        });
        files.commit();
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail("cannot write EXR {}: {}", path.string(), e.what());
    }
}

void write_image(const std::filesystem::path& path, const Image& image) {
    const std::string ext = lower_extension(path);
    if (ext == ".png") return write_png(path, image);
    if (ext == ".jpg" || ext == ".jpeg") return write_jpeg(path, image);
    if (ext == ".exr") return write_exr(path, image);
    fail("unsupported image format '{}' for {} (expected .png, .jpg, .jpeg or .exr)", ext, path.string());
}

}  // namespace surfscatter::io
