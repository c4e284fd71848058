#include "surfscatter/heightmap/prepare.hpp"

#include <algorithm>
#include <cstddef>
#include <cmath>

#include <fmt/format.h>

namespace surfscatter::heightmap {

double wrap_jump_ratio(const HeightMap& map) {
    const std::size_t nx = map.nx(), ny = map.ny();
    double ratio = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        const std::size_t n = axis == 0 ? nx : ny, m = axis == 0 ? ny : nx;
        auto h = [&](std::size_t i, std::size_t j) { return axis == 0 ? map(i, j) : map(j, i); };
        double jump = 0.0, step = 0.0;
        for (std::size_t j = 0; j < m; ++j) {
            const double d = h(0, j) - h(n - 1, j);
            jump += d * d;
            for (std::size_t i = 0; i + 1 < n; ++i) {
                const double s = h(i + 1, j) - h(i, j);
                step += s * s;
            }
        }
        jump /= static_cast<double>(m);
        step /= static_cast<double>(m) * static_cast<double>(n - 1);
        ratio = std::max(ratio, step > 0.0 ? jump / step : (jump > 0.0 ? HUGE_VAL : 1.0));
    }
    return ratio;
}

bool is_periodic(const HeightMap& map) {
    if (map.source.periodic) return *map.source.periodic;
    return !map.has_invalid() && wrap_jump_ratio(map) <= kPeriodicJumpRatio;
}

PreparedMap prepare(const HeightMap& read, const Preparation& how) {
    Outliers outliers;
    HeightMap cleaned = apply_outlier_policy(read, how.outliers, outliers);
    const double read_rms = height_moments(read).rms;
    const double cleaned_rms = height_moments(cleaned).rms;
    HeightMap map = remove_form(cleaned, how.form);
    map.source.periodic = is_periodic(read);
    // The form is a least-squares projection: its rms and the residual's add in quadrature.
    const double residual_rms = height_moments(map).rms;
    const double form_rms = std::sqrt(std::max(0.0, cleaned_rms * cleaned_rms - residual_rms * residual_rms));
    return PreparedMap{std::move(map), how, std::move(outliers), read_rms, form_rms};
}

std::string describe(const PreparedMap& p) {
    return fmt::format("prepared: outliers {} ({} points), form {} (removed rms {:.4g} um), rms {:.4g} um (as read {:.4g} um)",
                       to_string(p.applied.outliers), p.outliers.count, to_string(p.applied.form), p.form_rms_um,
                       height_moments(p.map).rms, p.read_rms_um);
}

}  // namespace surfscatter::heightmap
