#include "surfscatter/heightmap/tmd.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {
constexpr std::string_view kTmdMagic("Binary TrueMap Data File v2.0\r\n\0", 32);
constexpr std::size_t kMaxCommentBytes = 256;
constexpr double kMmInUm = 1e3;  // TMD states lengths and heights in mm
}  // namespace

bool is_tmd(std::string_view head) { return head.substr(0, kTmdMagic.size()) == kTmdMagic; }

HeightMap read_tmd(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = parse::file_bytes(path);
    if (!is_tmd(bytes)) fail("{}: not a TMD file (first line is not 'Binary TrueMap Data File v2.0')", path);

    const std::size_t comment_end = bytes.find('\0', kTmdMagic.size());
    if (comment_end == std::string::npos || comment_end - kTmdMagic.size() > kMaxCommentBytes)
        fail("{}: TMD comment after the first line is not NUL-terminated within {} bytes", path, kMaxCommentBytes);
    std::string_view comment = std::string_view(bytes).substr(kTmdMagic.size(), comment_end - kTmdMagic.size());
    while (!comment.empty() && (comment.back() == '\n' || comment.back() == '\r')) comment.remove_suffix(1);

    binary::Cursor in(bytes, path, comment_end + 1);
    const std::uint32_t nx = in.u32("the number of columns");
    const std::uint32_t ny = in.u32("the number of rows");
    const double length_x = in.f32("the length along x");
    const double length_y = in.f32("the length along y");
    const double offset_x = in.f32("the offset along x");
    const double offset_y = in.f32("the offset along y");
    binary::require_grid_size(path, nx, ny, "TMD columns x rows");
    const std::uint64_t data_bytes = 4ull * nx * ny;
    if (in.remaining() != data_bytes)
        fail("{}: TMD columns x rows = {} x {} needs {} bytes of float32 heights after the {}-byte header, the file has "
             "{}{}",
             path, nx, ny, data_bytes, in.position(), in.remaining(),
             in.remaining() < data_bytes ? " (truncated)" : " (trailing bytes)");
    if (!(std::isfinite(length_x) && length_x > 0.0) || !(std::isfinite(length_y) && length_y > 0.0))
        fail("{}: TMD lengths {} x {} mm must be positive", path, length_x, length_y);
    if (!std::isfinite(offset_x) || !std::isfinite(offset_y))
        fail("{}: TMD offsets {}, {} mm are not finite", path, offset_x, offset_y);

    std::vector<double> heights(static_cast<std::size_t>(nx) * ny);
    std::vector<std::uint8_t> valid(heights.size(), 1);
    for (std::size_t i = 0; i < heights.size(); ++i) {
        const float value = in.f32("a height");
        if (std::isinf(value)) fail("{}: height {} (column {}, row {}) is infinite", path, i, i % nx, i / nx);
        if (std::isnan(value)) valid[i] = 0;
        else heights[i] = static_cast<double>(value) * kMmInUm;
    }
    HeightMap map(nx, ny, length_x * kMmInUm / nx, length_y * kMmInUm / ny, std::move(heights), std::move(valid), path);
    map.offset_x = offset_x * kMmInUm;
    map.offset_y = offset_y * kMmInUm;
    map.title = std::string(parse::trim(comment));
    map.source.format = "TrueMap TMD (.tmd)";
    map.source.reader = "native:tmd";
    map.source.height_unit_um = kMmInUm;
    return map;
}

}  // namespace surfscatter::heightmap
