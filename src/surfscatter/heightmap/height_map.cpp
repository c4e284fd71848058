#include "surfscatter/heightmap/height_map.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

void require_valid_spacing(double spacing_um, const std::string& what) {
    if (!(spacing_um >= kMinSpacingUm && spacing_um <= kMaxSpacingUm))
        fail("{} must be between {} and {} um, got {}", what, kMinSpacingUm, kMaxSpacingUm, spacing_um);
}

HeightMap::HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um,
                     std::vector<double> heights_um, const std::string& origin)
    : HeightMap(nx, ny, spacing_x_um, spacing_y_um, std::move(heights_um), {}, origin) {}

HeightMap::HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um,
                     std::vector<double> heights_um, std::vector<std::uint8_t> validity, const std::string& origin)
    : nx_(nx), ny_(ny), spacing_x_(spacing_x_um), spacing_y_(spacing_y_um), heights_(std::move(heights_um)),
      valid_(std::move(validity)), origin_(origin) {
    if (nx < kMinHeightMapSize || ny < kMinHeightMapSize)
        fail("{}: grid is {} x {} samples; at least {} x {} are needed", origin, nx, ny, kMinHeightMapSize,
             kMinHeightMapSize);
    require_valid_spacing(spacing_x_um, origin + ": x pixel spacing");
    require_valid_spacing(spacing_y_um, origin + ": y pixel spacing");
    if (heights_.size() != nx * ny)
        fail("{}: {} heights given for a {} x {} grid", origin, heights_.size(), nx, ny);
    if (!valid_.empty() && valid_.size() != heights_.size())
        fail("{}: validity mask has {} points for a {} x {} grid", origin, valid_.size(), nx, ny);
    valid_count_ = 0;
    for (std::size_t i = 0; i < heights_.size(); ++i) {
        if (!valid(i)) {
            heights_[i] = 0.0;
            continue;
        }
        if (!(std::abs(heights_[i]) <= kMaxHeightUm))
            fail("{}: height at column {}, row {} is {} um (every height must be finite and within +-{:g} um)", origin,
                 i % nx, i / nx, heights_[i], kMaxHeightUm);
        ++valid_count_;
    }
    if (valid_count_ == 0) fail("{}: every one of the {} x {} points is invalid", origin, nx, ny);
    if (valid_count_ == heights_.size()) valid_.clear();  // canonical: no mask when nothing is masked
}

HeightMap HeightMap::with_heights(std::vector<double> heights_um) const {
    HeightMap result(nx_, ny_, spacing_x_, spacing_y_, std::move(heights_um), valid_, origin_);
    result.offset_x = offset_x;
    result.offset_y = offset_y;
    result.title = title;
    result.source = source;
    return result;
}

std::string describe(const HeightMap& map) {
    return fmt::format("{}: {}, {} x {} points of {:.4g} x {:.4g} um, {:.2f} % valid",
                       map.origin(),
                       map.source.format.empty() ? "synthesized" : map.source.format, map.nx(), map.ny(),
                       map.spacing_x(), map.spacing_y(), 100.0 * map.valid_fraction());
}

void require_valid_fraction(const HeightMap& map, double minimum, const std::string& what) {
    if (map.valid_fraction() < minimum)
        fail("{}: only {:.1f} % of the {} x {} points are valid; {} needs at least {:.0f} %", map.origin(),
             100.0 * map.valid_fraction(), map.nx(),
             map.ny(), what, 100.0 * minimum);
}

}  // namespace surfscatter::heightmap
