// Smoothed slope variances of elliptical surfaces (elliptical_slopes.hpp) against the elliptical Gaussian's closed
// form and, for KC (gamma 2.5, whose unsmoothed slopes diverge, and 4), a direct quadrature over the zeta-plane of
// zeta_u^2 P-hat(zeta) e^{-s^2 |zeta|^2} with the elliptical KC PSD written here.
#include <cmath>

#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/surface/elliptical_slopes.hpp"

namespace surfscatter::surface {
namespace {

TEST(EllipticalSlopes, GaussianMatchesTheClosedForm) {
    // P-hat = LU LV / (4 pi) exp(-(LU^2 zeta_u^2 + LV^2 zeta_v^2) / 4) times e^{-s^2 |zeta|^2}: a Gaussian integral,
    // <h_u^2> = sigma^2 LU LV / (8 a_u^{3/2} a_v^{1/2}), a_u = LU^2 / 4 + s^2 (and u <-> v).
    const double sigma = 0.3, lu = 2.0, lv = 0.5;
    for (double s : {0.0, 0.1, 0.7, 5.0})
        for (double angle : {0.0, 40.0, 90.0}) {
            const EllipticalStatistics e(std::make_shared<GaussianAcv>(sigma, lu), lv, angle * kDegree);
            const double au = 0.25 * lu * lu + s * s, av = 0.25 * lv * lv + s * s;
            const double scale = sigma * sigma * lu * lv / 8.0;
            const Vec2 got = smoothed_slope_variances_lay(e, s);
            EXPECT_NEAR(got.x / (scale / (std::pow(au, 1.5) * std::sqrt(av))), 1.0, 1e-9) << s << " " << angle;
            EXPECT_NEAR(got.y / (scale / (std::sqrt(au) * std::pow(av, 1.5))), 1.0, 1e-9) << s << " " << angle;
        }
}

TEST(EllipticalSlopes, KcMatchesAQuadratureOverTheZetaPlane) {
    const double sigma = 0.1, lu = 1.0;
    for (double gamma : {2.5, 4.0})
        for (double lv : {0.2, 3.0}) {
            const double s = 0.3, stretch = lv / lu;
            // The elliptical KC PSD of unit mass, in the lay frame (the lay angle only rotates the zeta-plane).
            const auto psd = [&](double zu, double zv) {
                return stretch * (gamma - 1) * lu * lu / kTwoPi *
                       std::pow(1 + lu * lu * (zu * zu + stretch * stretch * zv * zv), -0.5 * (gamma + 1));
            };
            double moments[2];
            for (int axis = 0; axis < 2; ++axis) {
                const auto along_phi = [&](double phi) {
                    const double c = std::cos(phi), sn = std::sin(phi), w = axis == 0 ? c * c : sn * sn;
                    const auto radial = [&](double r) {
                        return r * r * r * w * psd(r * c, r * sn) * std::exp(-s * s * r * r);
                    };
                    return math::integrate_adaptive(radial, 0.0, 40.0 / s, 1e-11);
                };
                moments[axis] = 4 * sigma * sigma * math::integrate_adaptive(along_phi, 0.0, 0.5 * kPi, 1e-10);
            }
            const EllipticalStatistics e(std::make_shared<KCorrelation>(sigma, lu, gamma), lv, 25 * kDegree);
            const Vec2 got = smoothed_slope_variances_lay(e, s);
            EXPECT_NEAR(got.x / moments[0], 1.0, 1e-6) << gamma << " " << lv;
            EXPECT_NEAR(got.y / moments[1], 1.0, 1e-6) << gamma << " " << lv;
        }
}

TEST(EllipticalSlopes, UnsmoothedIsTheSlopeCovarianceAndNegativeSmoothingIsRefused) {
    const EllipticalStatistics e(std::make_shared<KCorrelation>(0.1, 1.0, 4.0), 0.5, 0.3);
    const Vec2 a = smoothed_slope_variances_lay(e, 0.0), b = e.slope_variances_lay();
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.y, b.y);
    // A smoothing far below LV leaves the slopes (finite for gamma 4) unchanged to its own order, s / LV for gamma 4.
    const Vec2 c = smoothed_slope_variances_lay(e, 1e-8);
    EXPECT_NEAR(c.x / b.x, 1.0, 1e-6);
    EXPECT_NEAR(c.y / b.y, 1.0, 1e-6);
    EXPECT_THROW(smoothed_slope_variances_lay(e, -1.0), Error);
}

}  // namespace
}  // namespace surfscatter::surface
