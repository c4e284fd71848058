// Mitsuba's `tent` reconstruction filter.
//
// Supported: `radius` (pixels, default 1). f(x) = max(0, 1 - |x| / radius).
// Differences: none in expectation (filter importance sampling, filter.hpp).
#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

namespace {
double tent_profile(double x, const double* p) { return std::max(0.0, 1 - std::abs(x) / p[0]); }
}  // namespace

FilterPtr tent(Properties& props) {
    const double radius = props.get_float("radius", 1.0);
    if (!(radius > 0)) props.fail_param("radius", "tent radius must be positive, got {}", radius);
    return std::make_shared<ReconstructionFilter>("tent", radius, tent_profile, std::vector<double>{radius});
}

}  // namespace surfscatter::render::plugins
