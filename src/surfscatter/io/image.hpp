#pragma once
// Image files: PNG and JPEG (through raster.hpp: libpng, libjpeg) and OpenEXR 3 (float channels).
//
// An Image holds float samples, row-major with the top row first and channels interleaved (1 = grey, 2 = grey +
// alpha, 3 = RGB, 4 = RGBA). No transfer function is applied by this module: PNG/JPEG samples come back as the stored 8-bit code
// values divided by 255 (sRGB-encoded for ordinary photographs), EXR samples as stored (linear by convention).
// Encoding and decoding sRGB is the caller's job (spectrum/color.hpp), so that there is one place for it.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfscatter::io {

struct Image {
    int width = 0;
    int height = 0;
    int channels = 0;          // 1 to 4
    std::vector<float> pixels; // width * height * channels

    Image() = default;
    Image(int width_, int height_, int channels_, float fill = 0.0f);

    float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
    bool empty() const { return pixels.empty(); }

private:
    std::size_t index(int x, int y, int c) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                   static_cast<std::size_t>(channels) +
               static_cast<std::size_t>(c);
    }
};

// Reads .png, .jpg/.jpeg, .exr or .hdr (chosen by extension, case-insensitive). PNG: 3 channels (grey is expanded to
// RGB), 4 if the file has alpha (or a transparent colour in RGB or palette files); 16-bit samples are kept (divided
// by 65535, no gamma chunk applied). JPEG: 3; a truncated JPEG is an error. Decoder warnings are printed as one
// "surfscatter: warning:" line. EXR: R, G, B (a Y-only file is
// expanded to RGB) plus A if present. HDR: Radiance RGBE (flat or run-length encoded scanlines, -Y H +X W
// orientation), linear RGB divided by the header's EXPOSURE as the Radiance format specifies.
// Throws Error naming the file on a missing file, an unknown extension or a decoder failure.
Image read_image(const std::filesystem::path& path);

// Writes by extension: .png (8-bit; samples clamped to [0, 1] and rounded; 1 to 4 channels), .jpg/.jpeg (quality 95;
// 1 or 3 channels), .exr (32-bit float, ZIP compression; channels Y, Y A, R G B or R G B A).
void write_image(const std::filesystem::path& path, const Image& image);
void write_png(const std::filesystem::path& path, const Image& image);
void write_jpeg(const std::filesystem::path& path, const Image& image, int quality = 95);
void write_exr(const std::filesystem::path& path, const Image& image);
// An EXR with the given channel names (one per image channel, e.g. X Y Z A) and sample type, ZIP compression.
enum class ExrPixelType { half, float32 };
void write_exr(const std::filesystem::path& path, const Image& image, const std::vector<std::string>& channels,
               ExrPixelType type);

}  // namespace surfscatter::io
