// FFTLog Hankel transform against the closed-form KC and Gaussian pairs (THEORY.md 2.5 accuracy rule).
#include <cmath>

#include <gtest/gtest.h>

#include "surfscatter/surface/hankel.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {
namespace {

double max_relative_error_kc(double gamma, double length, int n, double decades_each_side) {
    const KCorrelation kc(1.0, length, gamma);
    const FftLogHankel hankel(length * std::pow(10.0, -decades_each_side), length * std::pow(10.0, decades_each_side), n);
    std::vector<double> rho(n);
    for (int j = 0; j < n; ++j) rho[j] = kc.acv_normalized(hankel.r(j));
    const std::vector<double> out = hankel.transform(rho);
    double worst = 0.0;
    for (int j = 0; j < n; ++j) {
        const double zl = hankel.zeta(j) * length;
        if (zl < 0.01 || zl > 100.0) continue;
        const double expected = kc.psd_unit(hankel.zeta(j));
        worst = std::max(worst, std::abs(out[j] / (2.0 * M_PI) - expected) / expected);
    }
    return worst;
}

TEST(Hankel, KcPsdFromAcvTo1e6) {
    for (double gamma : {1.5, 2.0, 2.5, 3.0, 4.0}) {
        for (double length : {0.1, 1.0, 37.0}) {
            const double err = max_relative_error_kc(gamma, length, 4096, 8.0);
            EXPECT_LT(err, 1e-6) << "gamma " << gamma << " L " << length;
        }
    }
}

TEST(Hankel, GaussianPairIsSelfInverse) {
    // H0{exp(-r^2/l^2)} = (l^2/2) exp(-l^2 zeta^2/4); the exact pair checks the grid offset and normalisation.
    const double l = 2.0;
    const FftLogHankel hankel(1e-12, 1e4, 4096);
    std::vector<double> f(hankel.size());
    for (int j = 0; j < hankel.size(); ++j) f[j] = std::exp(-hankel.r(j) * hankel.r(j) / (l * l));
    const auto out = hankel.transform(f);
    for (int j = 0; j < hankel.size(); ++j) {
        const double z = hankel.zeta(j);
        if (z * l < 1e-3 || z * l > 8.0) continue;
        const double expected = 0.5 * l * l * std::exp(-0.25 * l * l * z * z);
        EXPECT_NEAR(out[j], expected, 1e-9 * expected + 1e-13) << "zeta " << z;
    }
}

}  // namespace
}  // namespace surfscatter::surface
