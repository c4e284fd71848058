#pragma once
// Integer-sample images in PNG, JPEG and TIFF files: the one binding of libpng, libjpeg and libtiff. The float images
// of image.hpp and the photographs of photo/ are both read and written through it.
//
// Why not OpenCV's imgcodecs: 94 of the CLI's 213 shared objects were there only for it (GDAL, GDCM, libheif, ...),
// and their relocations and static constructors cost every command 0.07 CPU s at start-up (docs/PERFORMANCE.md,
// "Where the time goes"). The samples decoded here are those OpenCV 4.6's imread(IMREAD_UNCHANGED |
// IMREAD_IGNORE_ORIENTATION) returns (tests/photo/test_raster_vs_opencv.cpp checks it), in R, G, B order.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"

namespace surfscatter::io {

struct Raster {
    int width = 0;
    int height = 0;
    int channels = 0;                    // 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
    int bit_depth = 8;                   // 8 or 16
    std::vector<std::uint16_t> samples;  // width * height * channels, top row first, channels interleaved
    std::string warnings;                // the decoder's warnings on a file it could decode, "; "-separated
    double pixels_per_metre = 0.0;       // PNG: the physical pixel density of a pHYs chunk in metres (0: none)

    Raster() = default;
    Raster(int width_, int height_, int channels_, int bit_depth_);  // zero samples; checks sizes and memory
    std::uint16_t& at(int x, int y, int c) { return samples[index(x, y, c)]; }
    std::uint16_t at(int x, int y, int c) const { return samples[index(x, y, c)]; }

private:
    std::size_t index(int x, int y, int c) const {
        return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) *
                   static_cast<std::size_t>(channels) +
               static_cast<std::size_t>(c);
    }
};

// A file that is not a PNG, JPEG or TIFF the decoders can read. what() is one line naming the file; `reason` is the
// decoder's own message; `truncated` says the file ends inside the image data (a JPEG decoder would otherwise
// return the missing part grey).
class RasterError : public Error {
public:
    RasterError(const std::filesystem::path& path, const std::string& reason_, bool truncated_);
    std::string reason;
    bool truncated;
};

// Largest PNG/JPEG/TIFF file read (docs/RELIABILITY.md): the file is read whole; an uncompressed 16-bit RGB TIFF of
// a 61-megapixel camera is 366 MB.
inline constexpr std::uint64_t kMaxRasterFileBytes = std::uint64_t{1} << 30;

// Decodes the first image of a PNG, JPEG or TIFF file, recognised by its content (not its extension). Channels and
// depth as stored: PNG grey 1, grey + alpha 4 (grey copied to RGB), RGB 3, RGBA or any with a transparency chunk 4,
// palettes expanded, 1/2/4-bit grey scaled to 8 bits, 16-bit kept; JPEG grey 1, else 3 (CMYK converted to RGB);
// TIFF 16-bit unsigned grey or RGB(A) as stored, anything else libtiff's RGBA reader turns into 8 bits (grey 1,
// else 3, 4 with an alpha sample; unassociated alpha is multiplied into the colour, as OpenCV's reader does). EXIF orientation is not applied. Throws RasterError when the file cannot be
// decoded and Error when it cannot be read or its image would not fit in memory.
Raster read_raster(const std::filesystem::path& path);

// Prints a raster's warnings, if any, as one line "surfscatter: warning: image '<path>': ..." on stderr.
void print_warnings(const std::filesystem::path& path, const Raster& raster);

// An image of a size read from a file header may not fit in memory: one clear error (naming `what` and the size)
// instead of std::bad_alloc. Images under 64 MiB are not checked.
void require_image_memory(double width, double height, double bytes_per_pixel, const std::string& what);

// A path's extension in lower case (".tif" for "A.TIF"): formats are named by it.
std::string lower_extension(const std::filesystem::path& path);

enum class RasterFormat { png, jpeg, tiff };
// .png, .jpg/.jpeg, .tif/.tiff (case-insensitive); false otherwise.
bool raster_format_by_extension(const std::filesystem::path& path, RasterFormat& format);

// Writes 1 to 4 channels: PNG 8- or 16-bit (no filters, deflate level 3: fast, files a few % larger; 8-bit ones
// with an sRGB chunk), TIFF 8- or 16-bit (LZW with horizontal differencing), JPEG 8-bit grey or RGB at
// `jpeg_quality` (4:2:0 chroma). Throws Error naming the file when it cannot be written or the format cannot hold
// the image.
void write_raster(const std::filesystem::path& path, const Raster& raster, RasterFormat format,
                  int jpeg_quality = 95);

}  // namespace surfscatter::io
