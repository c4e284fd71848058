// Elliptical statistics (elliptical_statistics.hpp) against the closed forms of the elliptical Gaussian
// C = sigma^2 exp(-(x_u/LU)^2 - (x_v/LV)^2), P-hat = LU LV / (4 pi) exp(-(LU^2 zeta_u^2 + LV^2 zeta_v^2) / 4), written
// here with the rotation of the convention; KC's stretch against 2-D quadrature of its unit mass.
#include <cmath>

#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"

namespace surfscatter::surface {
namespace {

struct Lay {
    double u, v;
};
Lay lay_components(double x, double y, double angle) {
    return {x * std::cos(angle) + y * std::sin(angle), -x * std::sin(angle) + y * std::cos(angle)};
}

TEST(EllipticalStatistics, GaussianMatchesTheEllipticalClosedForms) {
    const double sigma = 0.2, lu = 3.0, lv = 0.7;
    for (double angle_deg : {0.0, 30.0, 90.0, -125.0}) {
        const double a = angle_deg * kDegree;
        const EllipticalStatistics e(std::make_shared<GaussianAcv>(sigma, lu), lv, a);
        EXPECT_DOUBLE_EQ(e.stretch(), lv / lu);
        for (double x : {-1.3, 0.0, 0.4, 2.2})
            for (double y : {-0.8, 0.0, 1.1}) {
                const Lay z = lay_components(x, y, a);
                const double psd = lu * lv / (4 * kPi) * std::exp(-(lu * lu * z.u * z.u + lv * lv * z.v * z.v) / 4);
                EXPECT_NEAR(e.psd_unit({x, y}), psd, 1e-13 * psd + 1e-300) << angle_deg << " " << x << " " << y;
                const double rho = std::exp(-(z.u * z.u) / (lu * lu) - (z.v * z.v) / (lv * lv));
                EXPECT_NEAR(e.acv_normalized({x, y}), rho, 1e-13) << angle_deg << " " << x << " " << y;
            }
        const Vec2 slopes = e.slope_variances_lay();  // -d2C/dx_u^2 (0) = 2 sigma^2 / LU^2, likewise along v
        EXPECT_NEAR(slopes.x, 2 * sigma * sigma / (lu * lu), 1e-12);
        EXPECT_NEAR(slopes.y, 2 * sigma * sigma / (lv * lv), 1e-12);
        const Vec2 back = e.from_lay(e.to_lay({0.3, -1.7}));
        EXPECT_NEAR(back.x, 0.3, 1e-15);
        EXPECT_NEAR(back.y, -1.7, 1e-15);
    }
}

TEST(EllipticalStatistics, EqualLengthsAreTheIsotropicStatistics) {
    const auto kc = std::make_shared<KCorrelation>(0.1, 2.0, 2.5);
    const EllipticalStatistics e(kc, 2.0, 0.7);
    EXPECT_TRUE(e.isotropic());
    for (double x : {0.01, 0.3, 4.0})
        for (double y : {0.0, -0.2, 1.5}) {
            EXPECT_NEAR(e.psd_unit({x, y}), kc->psd_unit(std::hypot(x, y)), 1e-13 * kc->psd_unit(std::hypot(x, y)));
            EXPECT_NEAR(e.acv_normalized({x, y}), kc->acv_normalized(std::hypot(x, y)), 1e-14);
        }
}

TEST(EllipticalStatistics, KcKeepsUnitMassOverTheZetaPlane) {
    // Polar quadrature about the origin of the local frame (not the stretched one): azimuth and ln radius.
    for (double gamma : {2.0, 4.0}) {
        const EllipticalStatistics e(std::make_shared<KCorrelation>(0.1, 2.0, gamma), 0.5, 20 * kDegree);
        const double mass = math::integrate_adaptive(
            [&](double phi) {
                return math::integrate_adaptive(
                    [&](double t) {
                        const double z = std::exp(t);
                        return z * z * e.psd_unit({z * std::cos(phi), z * std::sin(phi)});
                    },
                    -30.0, 40.0, 1e-11);
            },
            0.0, kTwoPi, 1e-9);
        EXPECT_NEAR(mass, 1.0, 1e-6) << gamma;
    }
}

TEST(EllipticalStatistics, RefusesBadLengthsAndAngles) {
    const auto kc = std::make_shared<KCorrelation>(0.1, 2.0, 3.0);
    EXPECT_THROW(EllipticalStatistics(kc, 0.0, 0.0), Error);
    EXPECT_THROW(EllipticalStatistics(kc, -1.0, 0.0), Error);
    EXPECT_THROW(EllipticalStatistics(kc, 1.0, std::nan("")), Error);
    EXPECT_THROW(EllipticalStatistics(nullptr, 1.0, 0.0), Error);
}

}  // namespace
}  // namespace surfscatter::surface
