#pragma once
// Relative L1 distance of two scattered lobes at theta_i = 30 deg, int |f_a - f_b| cos / int f_b cos over the
// hemisphere (the refit-vs-exact comparison of test_refit.cpp and bench/table_refit_distance.cpp).
#include <cmath>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"

namespace surfscatter::bsdf::test {

inline double lobe_distance(const Bsdf& a, const Bsdf& b, double lambda) {
    const double theta = 30 * kDegree, s = std::sin(theta), c = std::cos(theta);
    const Vec3 wi(s, 0, c);
    auto integral = [&](bool difference) {
        return integrate_disc_adaptive(s, c, [&](double q, double phi, double cos2_theta_o) {
            const Vec3 wo(q * std::cos(phi) - s, q * std::sin(phi), std::sqrt(cos2_theta_o));
            const double fb = b.eval(wi, wo, lambda);
            return difference ? std::abs(a.eval(wi, wo, lambda) - fb) : fb;
        }, 1e-5).value;
    };
    return integral(true) / integral(false);
}

}  // namespace surfscatter::bsdf::test
