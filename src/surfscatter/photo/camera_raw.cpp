#include "surfscatter/photo/camera_raw.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>

#include <libraw.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

std::optional<Photo> read_camera_raw(const std::filesystem::path& path) {
    // LibRaw is a large object (hundreds of kilobytes of tables): keep it off the stack.
    auto raw = std::make_unique<LibRaw>();
    // Its default handlers print to stderr; the library reports through Error instead.
    raw->set_dataerror_handler(nullptr, nullptr);
    raw->set_memerror_handler(nullptr, nullptr);

    libraw_output_params_t& p = raw->imgdata.params;
    p.output_bps = 16;
    p.gamm[0] = 1.0;
    p.gamm[1] = 1.0;
    p.no_auto_bright = 1;
    p.adjust_maximum_thr = 0.0f;
    p.use_camera_wb = 1;
    p.highlight = 0;
    p.user_qual = 3;
    p.output_color = 1;
    p.user_flip = 0;

    const std::string name = path.string();
    // open_file only reads the headers: failing there (unknown format, or too short for one) means "not RAW".
    if (raw->open_file(name.c_str()) != LIBRAW_SUCCESS) return std::nullopt;
    const auto check = [&](int code, const char* step) {
        if (code != LIBRAW_SUCCESS)
            fail("camera RAW '{}' could not be decoded by LibRaw ({}: {})", name, step, libraw_strerror(code));
    };
    check(raw->unpack(), "unpack");
    check(raw->dcraw_process(), "process");
    int code = LIBRAW_SUCCESS;
    const std::unique_ptr<libraw_processed_image_t, void (*)(libraw_processed_image_t*)> image(
        raw->dcraw_make_mem_image(&code), &LibRaw::dcraw_clear_mem);
    check(image ? code : LIBRAW_UNSPECIFIED_ERROR, "output");
    if (image->type != LIBRAW_IMAGE_BITMAP || image->bits != 16 || (image->colors != 1 && image->colors != 3))
        fail("camera RAW '{}': LibRaw returned {} colours of {} bits (expected 1 or 3 of 16)", name,
             int(image->colors), int(image->bits));

    Photo photo;
    photo.bit_depth = 16;
    photo.rgb.create(image->height, image->width, CV_32FC3);
    const int colors = image->colors;
    for (int y = 0; y < image->height; ++y)
        for (int x = 0; x < image->width; ++x) {
            cv::Vec3f& px = photo.rgb.at<cv::Vec3f>(y, x);
            for (int c = 0; c < 3; ++c) {
                std::uint16_t sample;  // native byte order in LibRaw's 16-bit bitmaps; the buffer is unaligned
                const std::size_t index = (std::size_t(y) * image->width + x) * colors + (colors == 3 ? c : 0);
                std::memcpy(&sample, image->data + 2 * index, sizeof sample);
                px[c] = float(sample) / 65535.0f;
            }
        }
    const double focal = raw->imgdata.other.focal_len;
    if (std::isfinite(focal) && focal > 0.0) photo.focal_length_mm = focal;
    return photo;
}

}  // namespace surfscatter::photo
