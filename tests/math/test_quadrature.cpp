// math::integrate_adaptive_2d against closed forms: a narrow Gaussian peak in a corner of its rectangle, a product of
// square-root edges, a jump along a line of one coordinate, and a union of rectangles with tags.
#include <gtest/gtest.h>

#include <cmath>

#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::math {

TEST(Cubature2d, NarrowPeakSqrtEdgesAndJumpsToTheirTolerance) {
    const double pi = 3.14159265358979323846;
    // exp(-(x^2 + y^2) / w^2) over [0, 1]^2, peak of width 1e-3 at the corner: (sqrt(pi) w erf(1/w) / 2)^2; the
    // starting rectangles graded toward the corner (as callers must for narrow features).
    const double w = 1e-3;
    std::vector<Box2> graded;  // an L-shaped tiling shrinking 4-fold toward the corner
    double a = 1.0;
    while (a > 1e-6) {
        const double b = 0.25 * a;
        graded.push_back({b, a, 0.0, a});  // right strip
        graded.push_back({0.0, b, b, a});  // top strip
        a = b;
    }
    graded.push_back({0.0, a, 0.0, a});
    const auto peak = integrate_adaptive_2d([&](double x, double y, int) { return std::exp(-(x * x + y * y) / (w * w)); },
                                            graded, 1e-10, 0.0, 2'000'000);
    const double peak_exact = std::pow(0.5 * std::sqrt(pi) * w * std::erf(1.0 / w), 2);
    EXPECT_NEAR(peak.value / peak_exact, 1.0, 1e-9);
    EXPECT_LT(std::abs(peak.value - peak_exact), 10 * peak.error + 1e-20);

    // sqrt(x (1 - y)) over [0, 1]^2 = (2/3)^2: square-root edges resolved by bisection.
    const auto edges = integrate_adaptive_2d([](double x, double y, int) { return std::sqrt(x * (1.0 - y)); },
                                             {{0.0, 1.0, 0.0, 1.0}}, 1e-8, 0.0, 2'000'000);
    EXPECT_NEAR(edges.value, 4.0 / 9.0, 1e-7);

    // A jump at x = 0.3 (an edge of the starting rectangles) and tags selecting two integrands: 0.3 * 2 + 0.7 * 3.
    const auto jump = integrate_adaptive_2d([](double x, double, int tag) { return tag == 0 ? (x < 0.3 ? 2.0 : 3.0) : 1.0; },
                                            {{0.0, 0.3, 0.0, 1.0, 0}, {0.3, 1.0, 0.0, 1.0, 0}, {0.0, 1.0, 1.0, 2.0, 1}},
                                            1e-12, 0.0, 100'000);
    EXPECT_NEAR(jump.value, 0.3 * 2 + 0.7 * 3 + 1.0, 1e-12);
    EXPECT_LE(jump.evaluations, 100'000);
}

}  // namespace surfscatter::math
