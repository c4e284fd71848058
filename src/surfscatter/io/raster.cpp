#include "surfscatter/io/raster.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <csetjmp>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string_view>

#include <jpeglib.h>
#include <jerror.h>
#include <png.h>
#include <tiffio.h>

#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/resources.hpp"

namespace surfscatter::io {

void require_image_memory(double width, double height, double bytes_per_pixel, const std::string& what) {
    constexpr double kCheckAbove = 64.0 * 1024 * 1024;  // smaller images are not worth a look at /proc/meminfo
    const double bytes = width * height * bytes_per_pixel;
    if (bytes > kCheckAbove) require_memory(bytes, fmt::format("{} ({}x{})", what, width, height));
}

Raster::Raster(int width_, int height_, int channels_, int bit_depth_)
    : width(width_), height(height_), channels(channels_), bit_depth(bit_depth_) {
    if (width_ <= 0 || height_ <= 0) fail("image size must be positive, got {}x{}", width_, height_);
    if (channels_ < 1 || channels_ > 4) fail("image must have 1 to 4 channels, got {}", channels_);
    if (bit_depth_ != 8 && bit_depth_ != 16) fail("image samples must be 8 or 16 bits, got {}", bit_depth_);
    // The samples here, and the float image or photograph most callers make of them.
    require_image_memory(width_, height_, 6.0 * channels_, "an image");
    samples.assign(static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_) * static_cast<std::size_t>(channels_),
                   0);
}

// The libraries' messages may quote the file's own bytes (libtiff quotes tag values): printable, one line.
RasterError::RasterError(const std::filesystem::path& path, const std::string& reason_, bool truncated_)
    : Error(fmt::format("cannot decode image {}: {}", path.string(), printable(reason_, 300))),
      reason(printable(reason_, 300)),
      truncated(truncated_) {}

namespace {

void append(std::string& list, const std::string& message) {
    if (!list.empty()) list += "; ";
    list += message;
}

// Plausibility of a header's image size against the file's size, checked before allocating (docs/RELIABILITY.md):
// deflate's largest expansion, and for JPEG and TIFF a bound on pixels per byte of file far above any photograph
// (JPEG needs at least a bit per 8x8 block of most layouts, 512 pixels a byte; a blank fax page in CCITT G4 is
// about 12000 pixels a byte).
constexpr double kMaxDeflateRatio = 1032;
constexpr double kMaxPixelsPerFileByte = 16384;
// TIFF's decoded samples: LZW expands at most about 2730-fold (12-bit codes of runs up to 4096 bytes), deflate 1032.
constexpr double kMaxTiffExpansion = 4096;

std::string too_many_pixels(const char* format, double width, double height, std::size_t file_bytes) {
    return fmt::format("a {}x{} {} image is more than its {} bytes can hold (at most {} pixels a byte)", width, height,
                       format, file_bytes, kMaxPixelsPerFileByte);
}

// ---- PNG (libpng; its errors longjmp back to the function that called setjmp) ----
// Everything that changes between setjmp and a longjmp lives in these structures, owned by the caller, so that no
// local of the function with setjmp is left indeterminate.

struct PngState {
    const std::string* file = nullptr;  // the whole file (reading)
    std::size_t position = 0;
    std::vector<std::uint8_t> bytes;    // decoded (reading) or encoded (writing) rows, 16-bit samples big-endian
    std::vector<png_bytep> rows;
    std::string warnings;
    char error[256] = {};
};

void png_error_handler(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngState*>(png_get_error_ptr(png));
    std::snprintf(state->error, sizeof state->error, "%s", message);
    png_longjmp(png, 1);
}

void png_warning_handler(png_structp png, png_const_charp message) {
    auto* state = static_cast<PngState*>(png_get_error_ptr(png));
    try {
        append(state->warnings, std::string("libpng warning: ") + message);
    } catch (...) {  // no exception may cross libpng's frames; a lost warning is the lesser harm
    }
}

void png_read_bytes(png_structp png, png_bytep out, png_size_t count) {
    auto* state = static_cast<PngState*>(png_get_io_ptr(png));
    if (state->file->size() - state->position < count) png_error(png, "the file ends inside the image data");
    std::memcpy(out, state->file->data() + state->position, count);
    state->position += count;
}

void point_rows(PngState& state, std::size_t height, std::size_t row_bytes) {
    state.rows.resize(height);
    for (std::size_t y = 0; y < height; ++y) state.rows[y] = state.bytes.data() + y * row_bytes;
}

// OpenCV 4.6's transformations for IMREAD_UNCHANGED, so that the samples are the same. Returns false with
// state.error set when libpng fails; throws Error when the image would not fit in memory.
bool decode_png(PngState& state, Raster& raster) {
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, png_error_handler, png_warning_handler);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_read_struct(&png, nullptr, nullptr);
        std::snprintf(state.error, sizeof state.error, "libpng could not allocate its structures");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    png_set_read_fn(png, &state, png_read_bytes);
    png_read_info(png, info);
    const int color_type = png_get_color_type(png, info);
    const int depth = png_get_bit_depth(png, info);
    int channels = 1;
    if (color_type == PNG_COLOR_TYPE_RGB || color_type == PNG_COLOR_TYPE_PALETTE)
        channels = png_get_valid(png, info, PNG_INFO_tRNS) ? 4 : 3;
    else if (color_type == PNG_COLOR_TYPE_GRAY_ALPHA || color_type == PNG_COLOR_TYPE_RGB_ALPHA)
        channels = 4;
    const int width = static_cast<int>(png_get_image_width(png, info));
    const int height = static_cast<int>(png_get_image_height(png, info));
    // Deflate expands at most 1032-fold: a header claiming more rows than the file can hold is found before the
    // image is allocated.
    const double filtered_bytes = static_cast<double>(height) * (static_cast<double>(png_get_rowbytes(png, info)) + 1);
    if (filtered_bytes > kMaxDeflateRatio * static_cast<double>(state.file->size())) {
        std::snprintf(state.error, sizeof state.error,
                      "a %dx%d PNG image needs %.0f bytes of image data, more than its %zu bytes can hold", width,
                      height, filtered_bytes, state.file->size());
        png_destroy_read_struct(&png, &info, nullptr);
        return false;
    }
    try {  // no libpng frame is below this one: an exception may leave it
        raster = Raster(width, height, channels, depth == 16 ? 16 : 8);
    } catch (...) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw;
    }
    if (channels < 4)
        png_set_strip_alpha(png);
    else
        png_set_tRNS_to_alpha(png);
    if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if ((color_type & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if ((color_type & PNG_COLOR_MASK_COLOR) == 0 && channels == 4) png_set_gray_to_rgb(png);
    png_set_interlace_handling(png);
    png_uint_32 density_x = 0, density_y = 0;
    int density_unit = 0;
    if (png_get_pHYs(png, info, &density_x, &density_y, &density_unit) && density_unit == PNG_RESOLUTION_METER &&
        density_x == density_y)
        raster.pixels_per_metre = density_x;
    png_read_update_info(png, info);
    const std::size_t row_bytes = raster.samples.size() / static_cast<std::size_t>(height) * (raster.bit_depth / 8);
    if (png_get_rowbytes(png, info) != row_bytes) png_error(png, "unexpected row size after the transformations");
    try {
        state.bytes.resize(row_bytes * static_cast<std::size_t>(height));
        point_rows(state, static_cast<std::size_t>(height), row_bytes);
    } catch (...) {
        png_destroy_read_struct(&png, &info, nullptr);
        throw;
    }
    png_read_image(png, state.rows.data());
    png_read_end(png, nullptr);
    png_destroy_read_struct(&png, &info, nullptr);
    return true;
}

Raster read_png(const std::filesystem::path& path, const std::string& file) {
    PngState state;
    state.file = &file;
    Raster raster;
    if (!decode_png(state, raster)) throw RasterError(path, state.error, false);
    if (raster.bit_depth == 16)
        for (std::size_t i = 0; i < raster.samples.size(); ++i)
            raster.samples[i] = static_cast<std::uint16_t>(state.bytes[2 * i] << 8 | state.bytes[2 * i + 1]);
    else
        std::copy(state.bytes.begin(), state.bytes.end(), raster.samples.begin());
    raster.warnings = std::move(state.warnings);
    return raster;
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::filesystem::path& path) {
    File f(std::fopen(path.c_str(), "wb"));
    if (!f) fail("cannot open {} for writing: {}", path.string(), std::strerror(errno));
    return f;
}

bool encode_png(PngState& state, std::FILE* file, const Raster& raster) {
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, png_error_handler, png_warning_handler);
    png_infop info = png ? png_create_info_struct(png) : nullptr;
    if (!info) {
        png_destroy_write_struct(&png, nullptr);
        std::snprintf(state.error, sizeof state.error, "libpng could not allocate its structures");
        return false;
    }
    if (setjmp(png_jmpbuf(png))) {
        png_destroy_write_struct(&png, &info);
        return false;
    }
    png_init_io(png, file);
    static constexpr int kColorTypes[4] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                           PNG_COLOR_TYPE_RGB_ALPHA};
    png_set_IHDR(png, info, static_cast<png_uint_32>(raster.width), static_cast<png_uint_32>(raster.height),
                 raster.bit_depth, kColorTypes[raster.channels - 1], PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
                 PNG_FILTER_TYPE_DEFAULT);
    // 8-bit files are sRGB-encoded images (film, sheets) and say so, as libpng's simplified API wrote them; 16-bit
    // ones are photographs in the encoding the user chose, written without a colour chunk as OpenCV did.
    if (raster.bit_depth == 8) png_set_sRGB(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
    // The physical size of a printable image (a calibration board): pixels per metre, as pHYs holds it.
    if (raster.pixels_per_metre > 0.0) {
        const auto density = static_cast<png_uint_32>(std::lround(raster.pixels_per_metre));
        png_set_pHYs(png, info, density, density, PNG_RESOLUTION_METER);
    }
    // libpng's own "fast" choice (PNG_IMAGE_FLAG_FAST): a quarter of the default's deflate time.
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_NONE);
    png_set_compression_level(png, 3);
    png_write_info(png, info);
    png_write_image(png, state.rows.data());
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    return true;
}

void write_png(const std::filesystem::path& path, const Raster& raster) {
    PngState state;
    const std::size_t bytes_per_sample = static_cast<std::size_t>(raster.bit_depth / 8);
    state.bytes.resize(raster.samples.size() * bytes_per_sample);
    for (std::size_t i = 0; i < raster.samples.size(); ++i) {
        if (bytes_per_sample == 2) {
            state.bytes[2 * i] = static_cast<std::uint8_t>(raster.samples[i] >> 8);
            state.bytes[2 * i + 1] = static_cast<std::uint8_t>(raster.samples[i] & 0xff);
        } else {
            state.bytes[i] = static_cast<std::uint8_t>(raster.samples[i]);
        }
    }
    point_rows(state, static_cast<std::size_t>(raster.height),
               static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.channels) * bytes_per_sample);
    File file = open_for_writing(path);
    errno = 0;
    if (!encode_png(state, file.get(), raster))  // libpng says "Write Error" where the system names the reason
        fail("cannot write PNG {}: {}", path.string(),
             std::ferror(file.get()) && errno != 0 ? std::strerror(errno) : state.error);
    if (std::fclose(file.release()) != 0) fail("cannot write PNG {}: {}", path.string(), std::strerror(errno));
}

// ---- JPEG (libjpeg; its fatal errors longjmp back here, its warnings are collected) ----

struct JpegState {
    jpeg_error_mgr manager;  // first: libjpeg hands back a pointer to it
    std::jmp_buf jump;
    char error[JMSG_LENGTH_MAX] = {};
    std::string warnings;
    bool truncated = false;
    std::vector<std::uint8_t> bytes;
};

void jpeg_error_exit(j_common_ptr info) {
    auto* state = reinterpret_cast<JpegState*>(info->err);
    (*info->err->format_message)(info, state->error);
    std::longjmp(state->jump, 1);
}

// Level -1 is a warning (corrupt data the decoder worked around, or the end of the file inside the image); levels
// 0 and up are trace messages.
void jpeg_emit_message(j_common_ptr info, int level) {
    if (level >= 0) return;
    auto* state = reinterpret_cast<JpegState*>(info->err);
    ++info->err->num_warnings;
    if (info->err->msg_code == JWRN_JPEG_EOF) state->truncated = true;
    char text[JMSG_LENGTH_MAX];
    (*info->err->format_message)(info, text);
    try {
        append(state->warnings, text);
    } catch (...) {  // no exception may cross libjpeg's frames
    }
}

struct JpegPixels {
    int width = 0, height = 0, channels = 0;
    bool cmyk = false;
};

// Grey files come back grey, CMYK/YCCK as CMYK (converted below as OpenCV does), the rest as RGB.
bool decode_jpeg(JpegState& state, jpeg_decompress_struct& info, const std::string& file, JpegPixels& pixels) {
    info.err = jpeg_std_error(&state.manager);
    state.manager.error_exit = jpeg_error_exit;
    state.manager.emit_message = jpeg_emit_message;
    if (setjmp(state.jump)) {
        jpeg_destroy_decompress(&info);
        return false;
    }
    jpeg_create_decompress(&info);
    jpeg_mem_src(&info, reinterpret_cast<const unsigned char*>(file.data()), static_cast<unsigned long>(file.size()));
    jpeg_read_header(&info, TRUE);
    if (double(info.image_width) * double(info.image_height) > kMaxPixelsPerFileByte * double(file.size())) {
        std::snprintf(state.error, sizeof state.error, "%s",
                      too_many_pixels("JPEG", info.image_width, info.image_height, file.size()).c_str());
        jpeg_destroy_decompress(&info);
        return false;
    }
    pixels.cmyk = info.num_components == 4;
    info.out_color_space = pixels.cmyk ? JCS_CMYK : info.num_components == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_start_decompress(&info);
    pixels.width = static_cast<int>(info.output_width);
    pixels.height = static_cast<int>(info.output_height);
    pixels.channels = info.output_components;
    const std::size_t row_bytes = static_cast<std::size_t>(pixels.width) * static_cast<std::size_t>(pixels.channels);
    try {  // no libjpeg frame is below this one
        require_image_memory(pixels.width, pixels.height, 7.0 * pixels.channels, "JPEG image");
        state.bytes.resize(row_bytes * static_cast<std::size_t>(pixels.height));
    } catch (...) {
        jpeg_destroy_decompress(&info);
        throw;
    }
    while (info.output_scanline < info.output_height) {
        JSAMPROW row = state.bytes.data() + static_cast<std::size_t>(info.output_scanline) * row_bytes;
        jpeg_read_scanlines(&info, &row, 1);
    }
    jpeg_finish_decompress(&info);
    jpeg_destroy_decompress(&info);
    return true;
}

Raster read_jpeg(const std::filesystem::path& path, const std::string& file) {
    JpegState state;
    jpeg_decompress_struct info;
    JpegPixels pixels;
    if (!decode_jpeg(state, info, file, pixels)) throw RasterError(path, state.error, false);
    if (state.truncated) throw RasterError(path, state.warnings, true);
    Raster raster(pixels.width, pixels.height, pixels.cmyk ? 3 : pixels.channels, 8);
    if (pixels.cmyk) {
        // OpenCV's CMYK conversion (grfmt_jpeg.cpp, icvCvt_CMYK2BGR_8u_C4C3R), for the same samples.
        for (std::size_t p = 0; p < raster.samples.size() / 3; ++p) {
            const std::uint8_t* cmyk = &state.bytes[4 * p];
            const int k = cmyk[3];
            for (int c = 0; c < 3; ++c) raster.samples[3 * p + c] = static_cast<std::uint16_t>(k - ((255 - cmyk[c]) * k >> 8));
        }
    } else {
        std::copy(state.bytes.begin(), state.bytes.end(), raster.samples.begin());
    }
    raster.warnings = std::move(state.warnings);
    return raster;
}

bool encode_jpeg(JpegState& state, jpeg_compress_struct& info, std::FILE* file, const Raster& raster, int quality) {
    info.err = jpeg_std_error(&state.manager);
    state.manager.error_exit = jpeg_error_exit;
    if (setjmp(state.jump)) {
        jpeg_destroy_compress(&info);
        return false;
    }
    jpeg_create_compress(&info);
    jpeg_stdio_dest(&info, file);
    info.image_width = static_cast<JDIMENSION>(raster.width);
    info.image_height = static_cast<JDIMENSION>(raster.height);
    info.input_components = raster.channels;
    info.in_color_space = raster.channels == 1 ? JCS_GRAYSCALE : JCS_RGB;
    jpeg_set_defaults(&info);
    jpeg_set_quality(&info, quality, TRUE);
    jpeg_start_compress(&info, TRUE);
    const std::size_t row_bytes = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.channels);
    while (info.next_scanline < info.image_height) {
        JSAMPROW row = state.bytes.data() + static_cast<std::size_t>(info.next_scanline) * row_bytes;
        jpeg_write_scanlines(&info, &row, 1);
    }
    jpeg_finish_compress(&info);
    jpeg_destroy_compress(&info);
    return true;
}

void write_jpeg(const std::filesystem::path& path, const Raster& raster, int quality) {
    if (raster.channels != 1 && raster.channels != 3)
        fail("cannot write {}: JPEG holds grey or RGB, not {} channels (no alpha)", path.string(), raster.channels);
    if (raster.bit_depth != 8) fail("cannot write {}: JPEG holds 8-bit samples, not {}-bit", path.string(), raster.bit_depth);
    if (quality < 1 || quality > 100) fail("cannot write {}: JPEG quality must be 1 to 100, got {}", path.string(), quality);
    JpegState state;
    state.bytes.assign(raster.samples.begin(), raster.samples.end());  // 8-bit samples: no narrowing of values
    File file = open_for_writing(path);
    jpeg_compress_struct info;
    if (!encode_jpeg(state, info, file.get(), raster, quality)) fail("cannot write JPEG {}: {}", path.string(), state.error);
    if (std::fclose(file.release()) != 0) fail("cannot write JPEG {}: {}", path.string(), std::strerror(errno));
}

// ---- TIFF (libtiff; errors come back as return values, their text through the handler) ----

struct TiffState {
    const std::string* file = nullptr;
    std::uint64_t position = 0;
    std::string error;
};

int tiff_error_handler(TIFF*, void* user_data, const char* module, const char* format, va_list arguments) {
    auto* state = static_cast<TiffState*>(user_data);
    char text[512];
    std::vsnprintf(text, sizeof text, format, arguments);
    try {
        if (state->error.empty()) state->error = module && *module ? std::string(module) + ": " + text : text;
    } catch (...) {
    }
    return 1;
}
// OpenCV does not show libtiff's warnings (mostly tags it does not know) and neither do we.
int tiff_warning_handler(TIFF*, void*, const char*, const char*, va_list) { return 1; }

tmsize_t tiff_read(thandle_t handle, void* out, tmsize_t count) {
    auto* state = static_cast<TiffState*>(handle);
    const std::uint64_t size = state->file->size();
    const std::uint64_t start = std::min(state->position, size);
    const std::uint64_t n = std::min<std::uint64_t>(static_cast<std::uint64_t>(count), size - start);
    std::memcpy(out, state->file->data() + start, n);
    state->position = start + n;
    return static_cast<tmsize_t>(n);
}
tmsize_t tiff_no_write(thandle_t, void*, tmsize_t) { return 0; }
toff_t tiff_seek(thandle_t handle, toff_t offset, int whence) {
    auto* state = static_cast<TiffState*>(handle);
    const std::uint64_t base = whence == SEEK_CUR ? state->position : whence == SEEK_END ? state->file->size() : 0;
    state->position = base + offset;
    return state->position;
}
int tiff_close(thandle_t) { return 0; }
toff_t tiff_size(thandle_t handle) { return static_cast<TiffState*>(handle)->file->size(); }
int tiff_no_map(thandle_t, void**, toff_t*) { return 0; }
void tiff_no_unmap(thandle_t, void*, toff_t) {}

using Tiff = std::unique_ptr<TIFF, void (*)(TIFF*)>;

TIFFOpenOptions* tiff_options(TiffState& state) {
    TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
    TIFFOpenOptionsSetErrorHandlerExtR(options, tiff_error_handler, &state);
    TIFFOpenOptionsSetWarningHandlerExtR(options, tiff_warning_handler, nullptr);
    return options;
}

// 16-bit unsigned grey or RGB(A) samples as stored, contiguous (OpenCV reads these directly, everything else
// through libtiff's RGBA reader).
void read_tiff_samples(TIFF* tiff, const std::filesystem::path& path, TiffState& state, Raster& raster) {
    const auto fail_here = [&](const char* what) {
        throw RasterError(path, state.error.empty() ? what : state.error, false);
    };
    const std::size_t row_samples = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.channels);
    if (TIFFIsTiled(tiff)) {
        std::uint32_t tile_width = 0, tile_height = 0;
        TIFFGetField(tiff, TIFFTAG_TILEWIDTH, &tile_width);
        TIFFGetField(tiff, TIFFTAG_TILELENGTH, &tile_height);
        if (tile_width == 0 || tile_height == 0 || tile_width > 65536 || tile_height > 65536 ||
            TIFFTileSize64(tiff) != std::uint64_t{tile_width} * tile_height * raster.channels * 2)
            fail_here("bad tile size");
        // A tile's samples come from the file like the image's (tiles may overhang the image, so bound them apart).
        if (double(TIFFTileSize64(tiff)) > kMaxTiffExpansion * double(state.file->size()))
            throw RasterError(path, fmt::format("a {}x{} TIFF tile is more than the file's {} bytes can hold", tile_width,
                                                tile_height, state.file->size()), false);
        std::vector<std::uint16_t> tile(static_cast<std::size_t>(tile_width) * tile_height * raster.channels);
        for (std::uint32_t y0 = 0; y0 < static_cast<std::uint32_t>(raster.height); y0 += tile_height)
            for (std::uint32_t x0 = 0; x0 < static_cast<std::uint32_t>(raster.width); x0 += tile_width) {
                if (TIFFReadEncodedTile(tiff, TIFFComputeTile(tiff, x0, y0, 0, 0), tile.data(),
                                        static_cast<tmsize_t>(tile.size() * 2)) < 0)
                    fail_here("a tile could not be read");
                const std::uint32_t w = std::min<std::uint32_t>(tile_width, static_cast<std::uint32_t>(raster.width) - x0);
                const std::uint32_t h = std::min<std::uint32_t>(tile_height, static_cast<std::uint32_t>(raster.height) - y0);
                for (std::uint32_t y = 0; y < h; ++y)
                    std::copy_n(&tile[static_cast<std::size_t>(y) * tile_width * raster.channels],
                                static_cast<std::size_t>(w) * raster.channels,
                                &raster.samples[(y0 + y) * row_samples + static_cast<std::size_t>(x0) * raster.channels]);
            }
    } else {
        if (TIFFScanlineSize64(tiff) != std::uint64_t{row_samples} * 2) fail_here("unexpected scanline size");
        for (int y = 0; y < raster.height; ++y)
            if (TIFFReadScanline(tiff, &raster.samples[static_cast<std::size_t>(y) * row_samples], static_cast<std::uint32_t>(y)) < 0)
                fail_here("a scanline could not be read");
    }
}

Raster read_tiff(const std::filesystem::path& path, const std::string& file) {
    TiffState state;
    state.file = &file;
    TIFFOpenOptions* options = tiff_options(state);
    // No buffer libtiff needs for a valid file is larger than the decoded image (bounded below): a damaged strip or
    // tile size cannot make it allocate more.
    TIFFOpenOptionsSetMaxSingleMemAlloc(
        options, static_cast<tmsize_t>(2 * kMaxTiffExpansion * static_cast<double>(file.size()) + (16 << 20)));
    const Tiff tiff(TIFFClientOpenExt(path.c_str(), "rm", &state, tiff_read, tiff_no_write, tiff_seek, tiff_close,
                                      tiff_size, tiff_no_map, tiff_no_unmap, options),
                    &TIFFClose);
    TIFFOpenOptionsFree(options);
    if (!tiff) throw RasterError(path, state.error.empty() ? "not a TIFF file libtiff can open" : state.error, false);
    std::uint32_t width = 0, height = 0;
    std::uint16_t bits = 1, samples = 1, format = SAMPLEFORMAT_UINT, planar = PLANARCONFIG_CONTIG, photometric = 0;
    if (!TIFFGetField(tiff.get(), TIFFTAG_IMAGEWIDTH, &width) || !TIFFGetField(tiff.get(), TIFFTAG_IMAGELENGTH, &height))
        throw RasterError(path, "the TIFF has no image size", false);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_BITSPERSAMPLE, &bits);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLESPERPIXEL, &samples);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_SAMPLEFORMAT, &format);
    TIFFGetFieldDefaulted(tiff.get(), TIFFTAG_PLANARCONFIG, &planar);
    if (!TIFFGetField(tiff.get(), TIFFTAG_PHOTOMETRIC, &photometric))  // libtiff's RGBA reader assumes the same
        photometric = samples >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK;
    if (format == SAMPLEFORMAT_IEEEFP || format == SAMPLEFORMAT_COMPLEXIEEEFP || bits > 16)
        throw RasterError(path, fmt::format("{}-bit {} samples (expected 8- or 16-bit integers)", bits,
                                            format == SAMPLEFORMAT_IEEEFP ? "floating-point" : "integer"), false);
    if (double(width) * double(height) > kMaxPixelsPerFileByte * double(file.size()))
        throw RasterError(path, too_many_pixels("TIFF", width, height, file.size()), false);
    const double decoded_bytes = double(width) * double(height) * samples * bits / 8;
    if (decoded_bytes > kMaxTiffExpansion * double(file.size()))
        throw RasterError(path, fmt::format("a {}x{} TIFF image of {} {}-bit samples a pixel ({} bytes) is more than its {} "
                                            "bytes can hold (at most {} times)", width, height, samples, bits,
                                            decoded_bytes, file.size(), kMaxTiffExpansion), false);
    if (width > 1000000 || height > 1000000)
        throw RasterError(path, fmt::format("a {}x{} TIFF image is beyond the 1000000-pixel side read", width, height),
                          false);
    const bool grey = photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_MINISWHITE;
    const bool direct = bits == 16 && (photometric == PHOTOMETRIC_MINISBLACK || photometric == PHOTOMETRIC_RGB) &&
                        (samples == 1 || samples == 3 || samples == 4);
    if (direct) {
        if (format != SAMPLEFORMAT_UINT) throw RasterError(path, "signed 16-bit samples (expected unsigned)", false);
        if (planar != PLANARCONFIG_CONTIG)
            throw RasterError(path, "16-bit samples in separate planes are not supported", false);
        Raster raster(static_cast<int>(width), static_cast<int>(height), samples, 16);
        read_tiff_samples(tiff.get(), path, state, raster);
        return raster;
    }
    char message[1024] = {};
    if (!TIFFRGBAImageOK(tiff.get(), message)) throw RasterError(path, message, false);
    Raster raster(static_cast<int>(width), static_cast<int>(height), grey && samples == 1 ? 1 : samples == 2 || samples >= 4 ? 4 : 3, 8);
    require_image_memory(width, height, 4.0, "TIFF image");
    std::vector<std::uint32_t> rgba(static_cast<std::size_t>(width) * height);
    if (!TIFFReadRGBAImageOriented(tiff.get(), width, height, rgba.data(), ORIENTATION_TOPLEFT, 0))
        throw RasterError(path, state.error.empty() ? "libtiff could not decode the image" : state.error, false);
    for (std::size_t p = 0; p < rgba.size(); ++p) {
        const std::uint32_t v = rgba[p];
        const std::uint16_t channel[4] = {static_cast<std::uint16_t>(TIFFGetR(v)), static_cast<std::uint16_t>(TIFFGetG(v)),
                                          static_cast<std::uint16_t>(TIFFGetB(v)), static_cast<std::uint16_t>(TIFFGetA(v))};
        std::copy_n(channel, raster.channels, &raster.samples[p * static_cast<std::size_t>(raster.channels)]);
    }
    return raster;
}

void write_tiff(const std::filesystem::path& path, const Raster& raster) {
    TiffState state;
    TIFFOpenOptions* options = tiff_options(state);
    const Tiff tiff(TIFFOpenExt(path.c_str(), "w", options), &TIFFClose);
    TIFFOpenOptionsFree(options);
    if (!tiff) fail("cannot write TIFF {}: {}", path.string(), state.error.empty() ? std::strerror(errno) : state.error);
    TIFF* t = tiff.get();
    TIFFSetField(t, TIFFTAG_IMAGEWIDTH, static_cast<std::uint32_t>(raster.width));
    TIFFSetField(t, TIFFTAG_IMAGELENGTH, static_cast<std::uint32_t>(raster.height));
    TIFFSetField(t, TIFFTAG_BITSPERSAMPLE, static_cast<std::uint16_t>(raster.bit_depth));
    TIFFSetField(t, TIFFTAG_SAMPLESPERPIXEL, static_cast<std::uint16_t>(raster.channels));
    TIFFSetField(t, TIFFTAG_SAMPLEFORMAT, static_cast<std::uint16_t>(SAMPLEFORMAT_UINT));
    TIFFSetField(t, TIFFTAG_PLANARCONFIG, static_cast<std::uint16_t>(PLANARCONFIG_CONTIG));
    TIFFSetField(t, TIFFTAG_PHOTOMETRIC,
                 static_cast<std::uint16_t>(raster.channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK));
    if (raster.channels == 2 || raster.channels == 4) {
        const std::uint16_t extra = EXTRASAMPLE_UNASSALPHA;
        TIFFSetField(t, TIFFTAG_EXTRASAMPLES, static_cast<std::uint16_t>(1), &extra);
    }
    TIFFSetField(t, TIFFTAG_COMPRESSION, static_cast<std::uint16_t>(COMPRESSION_LZW));
    TIFFSetField(t, TIFFTAG_PREDICTOR, static_cast<std::uint16_t>(PREDICTOR_HORIZONTAL));
    TIFFSetField(t, TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(t, 0));
    const std::size_t row_samples = static_cast<std::size_t>(raster.width) * static_cast<std::size_t>(raster.channels);
    std::vector<std::uint8_t> row8(raster.bit_depth == 8 ? row_samples : 0);
    std::vector<std::uint16_t> row16(raster.bit_depth == 16 ? row_samples : 0);
    for (int y = 0; y < raster.height; ++y) {
        const std::uint16_t* source = &raster.samples[static_cast<std::size_t>(y) * row_samples];
        void* row = nullptr;
        if (raster.bit_depth == 8) {
            std::copy_n(source, row_samples, row8.begin());
            row = row8.data();
        } else {
            std::copy_n(source, row_samples, row16.begin());  // libtiff may swap bytes in place
            row = row16.data();
        }
        if (TIFFWriteScanline(t, row, static_cast<std::uint32_t>(y), 0) < 0)
            fail("cannot write TIFF {}: {}", path.string(), state.error.empty() ? "write failed" : state.error);
    }
    if (!TIFFFlush(t)) fail("cannot write TIFF {}: {}", path.string(), state.error.empty() ? "write failed" : state.error);
}

}  // namespace

std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return ext;
}

Raster read_raster(const std::filesystem::path& path) {
    const std::string file = read_input_file(path, "image file", kMaxRasterFileBytes);
    const auto starts_with = [&](std::string_view magic) { return std::string_view(file).substr(0, magic.size()) == magic; };
    if (starts_with("\x89PNG\r\n\x1a\n")) return read_png(path, file);
    if (starts_with("\xff\xd8\xff")) return read_jpeg(path, file);
    if (starts_with(std::string_view("II*\0", 4)) || starts_with(std::string_view("MM\0*", 4)) ||
        starts_with(std::string_view("II+\0", 4)) || starts_with(std::string_view("MM\0+", 4)))
        return read_tiff(path, file);
    throw RasterError(path, "not a PNG, JPEG or TIFF file", false);
}

void print_warnings(const std::filesystem::path& path, const Raster& raster) {
    if (!raster.warnings.empty())
        std::fprintf(stderr, "surfscatter: warning: image '%s': %s\n", path.c_str(), printable(raster.warnings, 300).c_str());
}

bool raster_format_by_extension(const std::filesystem::path& path, RasterFormat& format) {
    const std::string ext = lower_extension(path);
    if (ext == ".png") format = RasterFormat::png;
    else if (ext == ".jpg" || ext == ".jpeg") format = RasterFormat::jpeg;
    else if (ext == ".tif" || ext == ".tiff") format = RasterFormat::tiff;
    else return false;
    return true;
}

void write_raster(const std::filesystem::path& path, const Raster& raster, RasterFormat format, int jpeg_quality) {
    if (raster.width <= 0 || raster.height <= 0 || raster.channels < 1 || raster.channels > 4 ||
        (raster.bit_depth != 8 && raster.bit_depth != 16) ||
        raster.samples.size() != static_cast<std::size_t>(raster.width) * raster.height * raster.channels)
        fail("cannot write {}: not a valid image ({}x{}, {} channels, {} bits, {} samples)", path.string(), raster.width,
             raster.height, raster.channels, raster.bit_depth, raster.samples.size());
    write_atomically(path, [&](const std::filesystem::path& tmp) {
        switch (format) {
            case RasterFormat::png: return write_png(tmp, raster);
            case RasterFormat::jpeg: return write_jpeg(tmp, raster, jpeg_quality);
            case RasterFormat::tiff: return write_tiff(tmp, raster);
        }
    });
}

}  // namespace surfscatter::io
