#include "surfscatter/heightmap/nms.hpp"

#include <cmath>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/binary.hpp"
#include "surfscatter/heightmap/parse.hpp"

namespace surfscatter::heightmap {

namespace {
constexpr std::size_t kNameAt = 32;
constexpr std::string_view kNamePrefix = "OM_MS_";
constexpr std::string_view kName("OM_MS_2.0\0", 10);
constexpr std::size_t kTitleAt = 52, kTitleBytes = 64;
constexpr std::size_t kRangeAt = 16, kDataOffsetAt = 1352, kGridAt = 1368, kSpacingAt = 1376;
constexpr std::size_t kHeaderEnd = kSpacingAt + 16;
constexpr double kNmInUm = 1e-3;
constexpr double kFullScale = 65535.0;  // uint16 codes span [zmin, zmax]
}  // namespace

bool is_nms(std::string_view head) { return head.size() > kNameAt && head.substr(kNameAt, kNamePrefix.size()) == kNamePrefix; }

HeightMap read_nms(const std::filesystem::path& file) {
    const std::string path = file.string();
    const std::string bytes = parse::file_bytes(path);
    if (!is_nms(bytes)) fail("{}: not an NMS file (no 'OM_MS_' format name at byte {})", path, kNameAt);
    if (bytes.size() < kHeaderEnd) fail("{}: NMS header truncated: {} bytes, at least {} expected", path, bytes.size(), kHeaderEnd);
    if (std::string_view(bytes).substr(kNameAt, kName.size()) != kName)
        fail("{}: NMS format '{}' is not supported (only OM_MS_2.0)", path,
             printable(std::string_view(bytes).substr(kNameAt, bytes.find('\0', kNameAt) - kNameAt)));

    binary::Cursor in(bytes, path, kRangeAt);
    const double zmin = in.f64("zmin"), zmax = in.f64("zmax");
    in.seek(kDataOffsetAt, "data offset");
    const std::uint32_t data_offset = in.u32("the data offset");
    const std::uint32_t bytes_per_height = in.u32("the bytes per height");
    in.seek(kGridAt, "grid size");
    const std::uint32_t nx = in.u32("nx"), ny = in.u32("ny");
    const double dx_nm = in.f64("dx"), dy_nm = in.f64("dy");

    binary::require_grid_size(path, nx, ny, "NMS nx x ny");
    if (bytes_per_height != 2) fail("{}: NMS heights of {} bytes are not supported (2: uint16)", path, bytes_per_height);
    if (data_offset < kHeaderEnd) fail("{}: NMS data offset {} lies inside the header ({} bytes)", path, data_offset, kHeaderEnd);
    const std::uint64_t n = std::uint64_t{nx} * ny;
    const std::uint64_t with_heights = data_offset + 2 * n, with_intensity = with_heights + n;
    if (bytes.size() != with_heights && bytes.size() != with_intensity)
        fail("{}: NMS nx x ny = {} x {} at byte {} needs {} bytes (heights) or {} (with the intensity image), the file "
             "has {}",
             path, nx, ny, data_offset, with_heights, with_intensity, bytes.size());
    if (!(std::isfinite(dx_nm) && dx_nm > 0.0 && std::isfinite(dy_nm) && dy_nm > 0.0))
        fail("{}: NMS spacings dx = {} nm, dy = {} nm must be positive", path, dx_nm, dy_nm);
    if (!(std::isfinite(zmin) && std::isfinite(zmax) && zmax >= zmin))
        fail("{}: NMS height range zmin = {}, zmax = {} um is not a range", path, zmin, zmax);

    std::vector<double> heights(static_cast<std::size_t>(n));
    in.seek(data_offset, "the heights");
    const double step = (zmax - zmin) / kFullScale;
    for (double& h : heights) h = zmin + step * in.u16("a height");
    HeightMap map(nx, ny, dx_nm * kNmInUm, dy_nm * kNmInUm, std::move(heights), path);
    const std::string_view title = std::string_view(bytes).substr(kTitleAt, kTitleBytes);
    map.title = std::string(parse::trim(title.substr(0, title.find('\0'))));  // "Confocal Height Image"
    map.source.channel = map.title;  // the file holds an intensity image too
    map.source.format = "NanoFocus NMS (.nms)";
    map.source.reader = "native:nms";
    map.source.height_unit_um = 1.0;
    return map;
}

}  // namespace surfscatter::heightmap
