#pragma once
// A printable image as a one-page PDF: the page is the image at a given physical size, so that a board printed at
// 100 % has the sizes it was drawn with. Written here (about a hundred bytes of PDF around a deflated image) rather
// than through a PDF library: nothing else in the project needs one.
#include <filesystem>

#include "surfscatter/io/raster.hpp"

namespace surfscatter::io {

// The largest page side PDF readers take: 200 inches (Acrobat's limit), in metres.
inline constexpr double kMaxPdfPageMetres = 200.0 * 0.0254;

// Writes `raster` (8-bit grey or RGB) as the only content of a one-page PDF 1.4 whose page is `width_m` x
// `height_m` metres (PDF points of 1/72 inch; at most 200 inches a side, the largest page PDF readers take), the
// image deflated (zlib) and drawn over the whole page. Throws Error naming the file when it cannot be written, the
// raster is not 8-bit grey or RGB, or a size is not positive or too large.
void write_image_pdf(const std::filesystem::path& path, const Raster& raster, double width_m, double height_m);

}  // namespace surfscatter::io
