#include "surfscatter/surface/elliptical_statistics.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::surface {

EllipticalStatistics::EllipticalStatistics(std::shared_ptr<const RadialStatistics> radial, double corr_length_v_um,
                                           double lay_angle_rad)
    : radial_(std::move(radial)), corr_length_v_(corr_length_v_um), lay_angle_(lay_angle_rad) {
    if (!radial_) fail("elliptical statistics need radial statistics");
    require_surface_length(corr_length_v_um, "corr_length_v");
    if (!std::isfinite(lay_angle_rad)) fail("lay_angle must be finite, got {}", lay_angle_rad);
    stretch_ = corr_length_v_ / radial_->correlation_length();
    cos_ = std::cos(lay_angle_rad);
    sin_ = std::sin(lay_angle_rad);
}

double EllipticalStatistics::stretched_radius(Vec2 zeta_xy) const {
    const Vec2 uv = to_lay(zeta_xy);
    return std::hypot(uv.x, stretch_ * uv.y);
}

double EllipticalStatistics::acv_normalized(Vec2 r_xy) const {
    const Vec2 uv = to_lay(r_xy);
    return radial_->acv_normalized(std::hypot(uv.x, uv.y / stretch_));
}

Vec2 EllipticalStatistics::slope_variances_lay() const {
    const double half = 0.5 * radial_->mean_square_slope(0.0, std::numeric_limits<double>::infinity());
    return {half, half / (stretch_ * stretch_)};
}

std::string EllipticalStatistics::cache_key() const {
    return fmt::format("elliptical({},LV={:.17g},A={:.17g})", radial_->cache_key(), corr_length_v_, lay_angle_);
}

std::string EllipticalStatistics::shape_key() const {
    return fmt::format("elliptical({},LV={:.17g})", radial_->cache_key(), corr_length_v_);
}

}  // namespace surfscatter::surface
