// Mitsuba's `lanczos` reconstruction filter (windowed sinc).
//
// Supported: `lobes` (integer, default 3) = the radius in pixels; f(x) = sinc(x) sinc(x / lobes) for |x| <= lobes.
// Negative lobes give signed sample weights (filter.hpp).
// Differences: none in expectation.
#include <cmath>

#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

namespace {
double lanczos_profile(double x, const double* p) {
    x = std::abs(x);
    if (x < 1e-7) return 1.0;
    if (x > p[0]) return 0.0;
    const double a = kPi * x, b = a / p[0];
    return std::sin(a) * std::sin(b) / (a * b);
}
}  // namespace

FilterPtr lanczos(Properties& props) {
    const int lobes = props.get_int("lobes", 3);
    if (lobes < 1) props.fail_param("lobes", "lanczos lobes must be at least 1, got {}", lobes);
    return std::make_shared<ReconstructionFilter>("lanczos", lobes, lanczos_profile, std::vector<double>{double(lobes)});
}

}  // namespace surfscatter::render::plugins
