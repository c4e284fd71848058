#include "surfscatter/io/image.hpp"

#include <algorithm>
#include <cctype>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <jpeglib.h>
#include <png.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::io {

Image::Image(int width_, int height_, int channels_, float fill)
    : width(width_), height(height_), channels(channels_),
      pixels(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * static_cast<std::size_t>(channels_),
             fill) {
    if (width_ <= 0 || height_ <= 0) fail("image size must be positive, got {}x{}", width_, height_);
    if (channels_ != 1 && channels_ != 3 && channels_ != 4) fail("image must have 1, 3 or 4 channels, got {}", channels_);
}

namespace {

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

void check_writable(const std::filesystem::path& path, const Image& image) {
    if (image.empty() || image.width <= 0 || image.height <= 0)
        fail("cannot write an empty image to {}", path.string());
    if (image.channels != 1 && image.channels != 3 && image.channels != 4)
        fail("cannot write {}: an image must have 1, 3 or 4 channels, got {}", path.string(), image.channels);
    if (image.pixels.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
        fail("cannot write {}: pixel buffer size does not match {}x{}x{}", path.string(), image.width, image.height,
             image.channels);
}

std::uint8_t to_byte(float v) {
    if (!(v > 0.0f)) return 0;  // also maps NaN to 0
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(v * 255.0f + 0.5f);
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_file(const std::filesystem::path& path, const char* mode) {
    File f(std::fopen(path.c_str(), mode));
    if (!f) fail("cannot open {}: {}", path.string(), std::strerror(errno));
    return f;
}

// ---- PNG (simplified API) ----

Image read_png(const std::filesystem::path& path) {
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&png, path.c_str())) fail("cannot read PNG {}: {}", path.string(), png.message);
    const bool alpha = (png.format & PNG_FORMAT_FLAG_ALPHA) != 0;
    png.format = alpha ? PNG_FORMAT_RGBA : PNG_FORMAT_RGB;
    std::vector<std::uint8_t> bytes(PNG_IMAGE_SIZE(png));
    if (!png_image_finish_read(&png, nullptr, bytes.data(), 0, nullptr)) {
        png_image_free(&png);
        fail("cannot decode PNG {}: {}", path.string(), png.message);
    }
    Image image(static_cast<int>(png.width), static_cast<int>(png.height), alpha ? 4 : 3);
    for (std::size_t i = 0; i < bytes.size(); ++i) image.pixels[i] = static_cast<float>(bytes[i]) / 255.0f;
    return image;
}

// ---- JPEG (libjpeg; its fatal errors longjmp back here) ----

struct JpegError {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

void jpeg_error_exit(j_common_ptr info) {
    auto* error = reinterpret_cast<JpegError*>(info->err);
    (*info->err->format_message)(info, error->message);
    std::longjmp(error->jump, 1);
}

Image read_jpeg(const std::filesystem::path& path) {
    File file = open_file(path, "rb");
    jpeg_decompress_struct info;
    JpegError error;
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jpeg_error_exit;
    std::vector<std::uint8_t> bytes;
    int width = 0, height = 0;
    if (setjmp(error.jump)) {
        jpeg_destroy_decompress(&info);
        fail("cannot decode JPEG {}: {}", path.string(), error.message);
    }
    jpeg_create_decompress(&info);
    jpeg_stdio_src(&info, file.get());
    jpeg_read_header(&info, TRUE);
    info.out_color_space = JCS_RGB;
    jpeg_start_decompress(&info);
    width = static_cast<int>(info.output_width);
    height = static_cast<int>(info.output_height);
    bytes.resize(static_cast<std::size_t>(width) * height * 3);
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = bytes.data() + static_cast<std::size_t>(info.output_scanline) * width * 3;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    Image image(width, height, 3);
    for (std::size_t i = 0; i < bytes.size(); ++i) image.pixels[i] = static_cast<float>(bytes[i]) / 255.0f;
    return image;
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
        for (int c = 0; c < 3; ++c)
            frame.insert(grey ? "Y" : names[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride, 1, 1, 0.0));
        if (alpha) frame.insert("A", Imf::Slice(Imf::FLOAT, base + 3 * sizeof(float), x_stride, y_stride, 1, 1, 1.0));
        file.setFrameBuffer(frame);
        file.readPixels(window.min.y, window.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail("cannot read EXR {}: {}", path.string(), e.what());
    }
}

}  // namespace

Image read_image(const std::filesystem::path& path) {
    if (!std::filesystem::exists(path)) fail("image file not found: {}", path.string());
    const std::string ext = lower_extension(path);
    if (ext == ".png") return read_png(path);
    if (ext == ".jpg" || ext == ".jpeg") return read_jpeg(path);
    if (ext == ".exr") return read_exr(path);
    fail("unsupported image format '{}' for {} (expected .png, .jpg, .jpeg or .exr)", ext, path.string());
}

void write_png(const std::filesystem::path& path, const Image& image) {
    check_writable(path, image);
    png_image png;
    std::memset(&png, 0, sizeof png);
    png.version = PNG_IMAGE_VERSION;
    png.width = static_cast<png_uint_32>(image.width);
    png.height = static_cast<png_uint_32>(image.height);
    png.format = image.channels == 1 ? PNG_FORMAT_GRAY : (image.channels == 3 ? PNG_FORMAT_RGB : PNG_FORMAT_RGBA);
    std::vector<std::uint8_t> bytes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), bytes.begin(), to_byte);
    if (!png_image_write_to_file(&png, path.c_str(), 0, bytes.data(), 0, nullptr))
        fail("cannot write PNG {}: {}", path.string(), png.message);
}

void write_jpeg(const std::filesystem::path& path, const Image& image, int quality) {
    check_writable(path, image);
    if (image.channels == 4) fail("cannot write {}: JPEG has no alpha channel", path.string());
    File file = open_file(path, "wb");
    jpeg_compress_struct info;
    JpegError error;
    info.err = jpeg_std_error(&error.manager);
    error.manager.error_exit = jpeg_error_exit;
    std::vector<std::uint8_t> bytes(image.pixels.size());
    std::transform(image.pixels.begin(), image.pixels.end(), bytes.begin(), to_byte);
    if (setjmp(error.jump)) {
        jpeg_destroy_compress(&info);
        fail("cannot write JPEG {}: {}", path.string(), error.message);
    }
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, file.get());
    info.image_width = static_cast<JDIMENSION>(image.width);
    info.image_height = static_cast<JDIMENSION>(image.height);
    info.input_components = image.channels;
    info.in_color_space = image.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, std::clamp(quality, 1, 100), TRUE);
    jpeg_start_compress(&info, TRUE);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = bytes.data() + static_cast<std::size_t>(info.next_scanline) * image.width * image.channels;
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
}

void write_exr(const std::filesystem::path& path, const Image& image) {
    check_writable(path, image);
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* rgba[4] = {"R", "G", "B", "A"};
        const int stored = image.channels == 1 ? 1 : image.channels;
        for (int c = 0; c < stored; ++c)
            header.channels().insert(image.channels == 1 ? "Y" : rgba[c], Imf::Channel(Imf::FLOAT));
        Imf::OutputFile file(path.c_str(), header);
        Imf::FrameBuffer frame;
        const std::size_t x_stride = sizeof(float) * image.channels;
        const std::size_t y_stride = x_stride * image.width;
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.pixels.data()));
        for (int c = 0; c < stored; ++c)
            frame.insert(image.channels == 1 ? "Y" : rgba[c],
                         Imf::Slice(Imf::FLOAT, base + c * sizeof(float), x_stride, y_stride));
        file.setFrameBuffer(frame);
        file.writePixels(image.height);
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
