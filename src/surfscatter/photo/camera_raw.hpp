#pragma once
// Camera RAW files (DNG, CR2, NEF, ARW, RAF, ORF, RW2, ...) decoded by LibRaw (Debian's libraw-dev, thread-safe
// libraw_r) into the pipeline's linear R, G, B photograph. The settings, chosen so that the samples stay
// proportional to the light the sensor counted:
//   - black level subtracted and white level scaled to full scale, exactly as the file states them
//     (adjust_maximum_thr = 0: no "real maximum" guess from the image content, which would depend on the scene);
//   - the camera's as-shot white balance (use_camera_wb), the smallest multiplier being 1; highlight clipping
//     (highlight = 0), so a channel with a larger multiplier clips at 1 before its own white level;
//   - AHD demosaicing (user_qual = 3);
//   - the camera's matrix (DNG ColorMatrix, the file's embedded one, or LibRaw's table for the model) to linear
//     sRGB D65 (output_color = 1); colours outside the sRGB gamut clip at 0 and 1;
//   - linear 16-bit output: gamma 1/1, no automatic brightening (no_auto_bright), no rotation (user_flip = 0,
//     so pixels keep the sensor's geometry like OpenCV's IMREAD_IGNORE_ORIENTATION).
// So 1 = the white level of the least amplified channel (usually green) after white balance.
#include <filesystem>
#include <optional>

#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

// The photograph in `path`, with EXIF FocalLength from LibRaw's metadata (imgdata.other.focal_len) when the file
// has one; bit_depth is 16 (the depth LibRaw delivers). Returns nullopt when LibRaw cannot open the file as camera
// RAW (a format it does not know, or a header too short to tell); throws Error naming the file when it opens it but
// cannot decode it (truncated image data, corrupt, out of memory).
std::optional<Photo> read_camera_raw(const std::filesystem::path& path);

}  // namespace surfscatter::photo
