#include "surfscatter/io/pdf.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <zlib.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"

namespace surfscatter::io {
namespace {

constexpr double kPointsPerMetre = 72.0 / 0.0254;

std::string deflate(const std::vector<unsigned char>& bytes, const std::filesystem::path& path) {
    uLongf size = compressBound(static_cast<uLong>(bytes.size()));
    std::string out(size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(out.data()), &size, bytes.data(), static_cast<uLong>(bytes.size()), 9) !=
        Z_OK)
        fail("cannot compress the image of {}", path.string());
    out.resize(size);
    return out;
}

}  // namespace

void write_image_pdf(const std::filesystem::path& path, const Raster& raster, double width_m, double height_m) {
    if (raster.bit_depth != 8 || (raster.channels != 1 && raster.channels != 3))
        fail("{}: a PDF page holds an 8-bit grey or RGB image, not {} channels of {} bits", path.string(),
             raster.channels, raster.bit_depth);
    const double width_pt = width_m * kPointsPerMetre, height_pt = height_m * kPointsPerMetre;
    if (!(width_m > 0.0 && height_m > 0.0 && width_m <= kMaxPdfPageMetres && height_m <= kMaxPdfPageMetres))
        fail("{}: page {} x {} m must be positive and at most 200 inches (5.08 m) a side", path.string(), width_m,
             height_m);
    std::vector<unsigned char> bytes(raster.samples.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<unsigned char>(raster.samples[i]);
    const std::string image = deflate(bytes, path);

    // Objects 1-5: catalog, page tree, page, its content stream, the image. Offsets go into the cross-reference
    // table, which must give each object's byte position exactly.
    std::string pdf = "%PDF-1.4\n%\xe2\xe3\xcf\xd3\n";
    std::vector<std::size_t> offsets;
    const auto object = [&](const std::string& body) {
        offsets.push_back(pdf.size());
        pdf += fmt::format("{} 0 obj\n{}\nendobj\n", offsets.size(), body);
    };
    const std::string content = fmt::format("q {:.4f} 0 0 {:.4f} 0 0 cm /Im0 Do Q", width_pt, height_pt);
    object("<< /Type /Catalog /Pages 2 0 R >>");
    object("<< /Type /Pages /Kids [3 0 R] /Count 1 >>");
    object(fmt::format("<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {:.4f} {:.4f}] /Resources << /XObject << /Im0 "
                       "5 0 R >> >> /Contents 4 0 R >>",
                       width_pt, height_pt));
    object(fmt::format("<< /Length {} >>\nstream\n{}\nendstream", content.size(), content));
    object(fmt::format("<< /Type /XObject /Subtype /Image /Width {} /Height {} /ColorSpace /{} /BitsPerComponent 8 "
                       "/Interpolate false /Filter /FlateDecode /Length {} >>\nstream\n",
                       raster.width, raster.height, raster.channels == 1 ? "DeviceGray" : "DeviceRGB",
                       image.size()) +
           image + "\nendstream");
    const std::size_t xref = pdf.size();
    pdf += fmt::format("xref\n0 {}\n0000000000 65535 f \n", offsets.size() + 1);
    for (const std::size_t offset : offsets) pdf += fmt::format("{:010d} 00000 n \n", offset);
    pdf += fmt::format("trailer\n<< /Size {} /Root 1 0 R >>\nstartxref\n{}\n%%EOF\n", offsets.size() + 1, xref);
    write_file_atomically(path, pdf);
}

}  // namespace surfscatter::io
