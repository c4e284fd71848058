// Mitsuba's `gaussian` reconstruction filter (the default of hdrfilm).
//
// Supported: `stddev` (pixels, default 0.5). As Mitsuba: radius 4 stddev, and the Gaussian minus its value at the
// radius, f(x) = max(0, exp(-x^2 / (2 stddev^2)) - exp(-8)), so that the profile reaches 0 continuously.
// Differences: none in expectation (filter importance sampling, filter.hpp).
#include <cmath>

#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

// p[0] = stddev, p[1] = the Gaussian's value at the radius 4 stddev, exp(-8).
double gaussian_profile(double x, const double* p) {
    return std::max(0.0, std::exp(-x * x / (2 * p[0] * p[0])) - p[1]);
}

FilterPtr gaussian(Properties& props) {
    const double stddev = props.get_float("stddev", 0.5);
    if (!(stddev > 0)) props.fail_param("stddev", "gaussian stddev must be positive, got {}", stddev);
    return make_gaussian_filter(stddev);
}

}  // namespace surfscatter::render::plugins

namespace surfscatter::render {
FilterPtr make_gaussian_filter(double stddev) {
    return std::make_shared<ReconstructionFilter>("gaussian", 4 * stddev, plugins::gaussian_profile,
                                                  std::vector<double>{stddev, std::exp(-8.0)});
}
}  // namespace surfscatter::render
