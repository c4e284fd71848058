#pragma once
// The 4-point Lagrange cubic through nodes at 0, 1, 2, 3: the weights of the nodes' values at position t (exact for
// cubics; t in [1, 2] for the interval between the middle nodes, outside it for one-sided stencils at a table's
// ends). Written with multiplications by 1/6 and 1/2, not divisions: a division each cost a fifth of the 2-D lobe
// lookup (SpectrumLobes2d::shape) on the eval path.
#include <array>

namespace surfscatter::math {

inline std::array<double, 4> lagrange4_weights(double t) {
    constexpr double kSixth = 1.0 / 6.0;
    const double a = t - 1.0, b = t - 2.0, c = t - 3.0;
    return {-kSixth * (a * b * c), 0.5 * (t * b * c), -0.5 * (t * a * c), kSixth * (t * a * b)};
}

}  // namespace surfscatter::math
