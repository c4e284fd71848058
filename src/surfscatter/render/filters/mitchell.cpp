// Mitsuba's `mitchell` reconstruction filter (Mitchell & Netravali 1988 cubic), and the cubic shared with
// `catmullrom` (catmullrom.cpp, B = 0, C = 1/2).
//
// Supported: `B`, `C` (defaults 1/3, 1/3). Radius 2 pixels. The filter has negative lobes: samples carry signed
// weights (filter.hpp).
// Differences: none in expectation.
#include <cmath>

#include "surfscatter/render/plugins.hpp"

namespace surfscatter::render::plugins {

double mitchell_netravali_profile(double x, const double* p) {
    const double b = p[0], c = p[1];
    x = std::abs(x);
    const double x2 = x * x, x3 = x2 * x;
    if (x < 1) return ((12 - 9 * b - 6 * c) * x3 + (-18 + 12 * b + 6 * c) * x2 + (6 - 2 * b)) / 6;
    if (x < 2) return ((-b - 6 * c) * x3 + (6 * b + 30 * c) * x2 + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6;
    return 0.0;
}

FilterPtr mitchell(Properties& props) {
    const double b = props.get_float("B", 1.0 / 3), c = props.get_float("C", 1.0 / 3);
    return std::make_shared<ReconstructionFilter>("mitchell", 2.0, mitchell_netravali_profile, std::vector<double>{b, c});
}

}  // namespace surfscatter::render::plugins
