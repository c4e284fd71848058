// lagrange4_weights against the cubic they must reproduce exactly, inside and outside [1, 2] (one-sided stencils).
#include <algorithm>
#include <array>
#include <cmath>

#include <gtest/gtest.h>

#include "surfscatter/math/lagrange.hpp"

namespace surfscatter::math {
namespace {

TEST(Lagrange, FourPointWeightsReproduceCubics) {
    double worst = 0;
    for (const auto& [a, b, c, d] : {std::array{1.0, -2.0, 0.5, 0.25}, std::array{-0.3, 1.7, -1.1, 0.9}}) {
        auto cubic = [&](double x) { return ((d * x + c) * x + b) * x + a; };
        for (double t = -1.0; t <= 4.0; t += 0.01) {
            const auto w = lagrange4_weights(t);
            const double sum = w[0] * cubic(0) + w[1] * cubic(1) + w[2] * cubic(2) + w[3] * cubic(3);
            worst = std::max(worst, std::abs(sum - cubic(t)) / (1.0 + std::abs(cubic(t))));
        }
    }
    EXPECT_LT(worst, 1e-13);
    for (int j = 0; j < 4; ++j) {  // at a node, that node's value alone
        const auto w = lagrange4_weights(j);
        for (int m = 0; m < 4; ++m) EXPECT_EQ(w[std::size_t(m)], m == j ? 1.0 : 0.0) << j << " " << m;
    }
}

}  // namespace
}  // namespace surfscatter::math
