#pragma once
// Relative L1 distance of two scattered lobes at theta_i = 30 deg, int |f_a - f_b| cos / int f_b cos over the
// hemisphere (the refit-vs-exact comparison of test_refit.cpp and bench/table_refit_distance.cpp).
#include <cmath>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"

namespace surfscatter::bsdf::test {

inline double lobe_distance(const Bsdf& a, const Bsdf& b, double lambda) {
    const double theta = 30 * kDegree, s = std::sin(theta);
    const Vec3 wi(s, 0, std::cos(theta));
    auto integral = [&](bool difference) {
        return integrate_visible_disc(s, 1e-7, [&](double q, double phi) {
            const double ox = q * std::cos(phi) - s, oy = q * std::sin(phi), z2 = 1 - ox * ox - oy * oy;
            if (z2 <= 0) return 0.0;
            const Vec3 wo(ox, oy, std::sqrt(z2));
            const double fb = b.eval(wi, wo, lambda);
            return difference ? std::abs(a.eval(wi, wo, lambda) - fb) : fb;
        });
    };
    return integral(true) / integral(false);
}

}  // namespace surfscatter::bsdf::test
