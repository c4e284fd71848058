#include "surfscatter/surface/height_map_acv.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::surface {

namespace {

constexpr int kDirections = 360;       // over 180 degrees
constexpr double kStepsPerPixel = 4.0;  // radial steps per (smaller) pixel spacing

// The normalised ACF on the lag grid |tx| <= nx/2, |ty| <= ny/2, with bilinear interpolation in between.
class Acf {
public:
    explicit Acf(const heightmap::HeightMap& flat) : nx_(flat.nx()), ny_(flat.ny()), dx_(flat.spacing_x()), dy_(flat.spacing_y()) {
        std::vector<double> masked(flat.size()), mask(flat.size());
        for (std::size_t i = 0; i < flat.size(); ++i) {
            masked[i] = flat.valid(i) ? flat.heights()[i] : 0.0;
            mask[i] = flat.valid(i) ? 1.0 : 0.0;
        }
        products_ = heightmap::linear_autocorrelation(masked, nx_, ny_);
        pairs_ = flat.has_invalid() ? heightmap::linear_autocorrelation(mask, nx_, ny_) : std::vector<double>{};
        zero_ = lag(0, 0);
        if (!(zero_ > 0.0)) fail("{}: the map is flat after form removal; it has no ACF", flat.origin());
    }

    double max_lag_x() const { return static_cast<double>(nx_ / 2) * dx_; }
    double max_lag_y() const { return static_cast<double>(ny_ / 2) * dy_; }

    // ACF at lag (x, y) in um, |x| <= max_lag_x(), |y| <= max_lag_y().
    double operator()(double x, double y) const {
        const double u = x / dx_, v = y / dy_;
        const double fu = std::floor(u), fv = std::floor(v);
        const auto iu = static_cast<long>(fu), iv = static_cast<long>(fv);
        const double a = u - fu, b = v - fv;
        return ((1 - a) * (1 - b) * lag(iu, iv) + a * (1 - b) * lag(iu + 1, iv) + (1 - a) * b * lag(iu, iv + 1) +
                a * b * lag(iu + 1, iv + 1)) /
               zero_;
    }

private:
    // Unnormalised ACV at integer lag (tx, ty); pairs exist for every lag used (|t| <= n/2 keeps half the rows).
    double lag(long tx, long ty) const {
        const auto ex = static_cast<long>(2 * nx_), ey = static_cast<long>(2 * ny_);
        const auto index = static_cast<std::size_t>(((ty % ey + ey) % ey) * ex + (tx % ex + ex) % ex);
        if (pairs_.empty()) {
            const double count = static_cast<double>((static_cast<long>(nx_) - std::labs(tx)) *
                                                     (static_cast<long>(ny_) - std::labs(ty)));
            return products_[index] / count;
        }
        return pairs_[index] > 0.5 ? products_[index] / pairs_[index] : 0.0;  // pair counts are integers
    }

    std::size_t nx_, ny_;
    double dx_, dy_;
    std::vector<double> products_, pairs_;
    double zero_ = 0.0;
};

}  // namespace

AcvMeasures acv_measures(const heightmap::HeightMap& flat) {
    const Acf acf(flat);
    const double step = std::min(flat.spacing_x(), flat.spacing_y()) / kStepsPerPixel;
    const double radial_limit = std::min(acf.max_lag_x(), acf.max_lag_y());
    const auto radial_steps = static_cast<std::size_t>(radial_limit / step);

    AcvMeasures result;
    std::vector<double> azimuthal_sum(radial_steps + 1, 0.0);
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    bool longest_is_bound = false;
    for (int d = 0; d < kDirections; ++d) {
        const double theta = kPi * d / kDirections, c = std::cos(theta), s = std::sin(theta);
        // Farthest usable lag along this direction (inside |x| <= max_lag_x, |y| <= max_lag_y).
        double limit = std::numeric_limits<double>::infinity();
        if (std::abs(c) > 1e-12) limit = std::min(limit, acf.max_lag_x() / std::abs(c));
        if (std::abs(s) > 1e-12) limit = std::min(limit, acf.max_lag_y() / std::abs(s));
        double crossing = limit;
        bool bound = true;
        double previous = 1.0;
        for (std::size_t k = 1; static_cast<double>(k) * step <= limit; ++k) {
            const double r = static_cast<double>(k) * step, value = acf(r * c, r * s);
            if (k <= radial_steps) azimuthal_sum[k] += value;
            if (bound && value <= kAcfThreshold) {
                crossing = r - step * (kAcfThreshold - value) / (previous - value);
                bound = false;
                if (k > radial_steps) break;
            }
            if (!bound && k >= radial_steps) break;
            previous = value;
        }
        shortest = std::min(shortest, crossing);
        if (crossing > longest) {
            longest = crossing;
            longest_is_bound = bound;
            result.slowest_direction_deg = 180.0 * d / kDirections;
        }
    }
    result.autocorrelation_length_um = shortest;
    result.texture_aspect_ratio = shortest / longest;
    result.str_is_bound = longest_is_bound;

    // Azimuthal mean ACF falls to 1/e.
    const double threshold = std::exp(-1.0);
    result.correlation_length_um = radial_limit;
    double previous = 1.0;
    for (std::size_t k = 1; k <= radial_steps; ++k) {
        const double value = azimuthal_sum[k] / kDirections;
        if (value <= threshold) {
            result.correlation_length_um = step * (static_cast<double>(k) - (threshold - value) / (previous - value));
            break;
        }
        previous = value;
    }
    return result;
}

}  // namespace surfscatter::surface
