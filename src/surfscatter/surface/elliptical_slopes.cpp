#include "surfscatter/surface/elliptical_slopes.hpp"

#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::surface {

Vec2 smoothed_slope_variances_lay(const EllipticalStatistics& statistics, double smoothing_um) {
    require_non_negative(smoothing_um, "smoothing scale");
    if (smoothing_um == 0) return statistics.slope_variances_lay();
    const double s = statistics.stretch(), no_cutoff = std::numeric_limits<double>::infinity();
    const RadialStatistics& radial = statistics.radial();
    const auto smoothed = [&](double phi) {
        const double c = std::cos(phi), sn = std::sin(phi) / s;
        return radial.mean_square_slope(smoothing_um * std::sqrt(c * c + sn * sn), no_cutoff);
    };
    // The integrands are even about 0 and pi / 2: a quarter of the circle, times 4.
    const double quarter = 0.5 * kPi;
    const double u = math::integrate_adaptive([&](double phi) { return std::pow(std::cos(phi), 2) * smoothed(phi); },
                                              0.0, quarter, 1e-10);
    const double v = math::integrate_adaptive([&](double phi) { return std::pow(std::sin(phi), 2) * smoothed(phi); },
                                              0.0, quarter, 1e-10);
    return {4.0 * u / kTwoPi, 4.0 * v / (kTwoPi * s * s)};
}

}  // namespace surfscatter::surface
