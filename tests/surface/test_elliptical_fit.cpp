// The elliptical KC fit (elliptical_fit.hpp) of synthetic elliptical KC maps, and the synthesis from a 2-D PSD it is
// tested with (synthesis.hpp).
//
// Maps: 512 x 512 of 1 um, KC LU = 8 um, gamma = 2.5, LV / LU in {1, 0.5, 0.2}, A in {0, 30, 90, 135} deg (the band
// runs from ring 4 to half Nyquist: zeta LU from 0.2 to 12.6, zeta LV from 0.04 (ratio 0.2) up). Periodic, so the
// fit sees the rectangular window's exact periodogram.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <vector>

#include <fmt/format.h>

#include "heightmap/height_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/elliptical_fit.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter::surface;
namespace hm = surfscatter::heightmap;
using surfscatter::kPi;

namespace {

constexpr double kSigma = 0.05, kLengthU = 8.0, kGamma = 2.5, kSpacing = 1.0;
constexpr std::size_t kSize = 512;

ss::EllipticalStatistics elliptical(double ratio, double angle_deg, double gamma = kGamma) {
    return ss::EllipticalStatistics(std::make_shared<ss::KCorrelation>(kSigma, kLengthU, gamma), ratio * kLengthU,
                                    angle_deg * kPi / 180.0);
}

ss::EllipticalKcFit fit_of(const hm::HeightMap& map) { return ss::fit_surface(map).elliptical; }

// Signed difference of two lay angles modulo 180 deg, in [-90, 90).
double angle_difference(double a, double b) { return std::remainder(a - b, 180.0); }

using surfscatter::heightmap::test::turned;

}  // namespace

TEST(EllipticalSynthesis, IsotropicEllipseIsTheRadialSynthesis) {
    const ss::KCorrelation kc(kSigma, kLengthU, kGamma);
    const hm::HeightMap radial = ss::synthesize_surface(kc, {64, 48, 0.5}, 7);
    const hm::HeightMap stretched = ss::synthesize_surface(elliptical(1.0, 0.0), {64, 48, 0.5}, 7);
    EXPECT_EQ(radial.heights(), stretched.heights());
}

// The synthesised map's ACV against the elliptical Gaussian's closed form exp(-(x_u / LU)^2 - (x_v / LV)^2), written
// here, at lags along u, along v and between, by direct cyclic sums averaged over 4 maps (the scatter of one lag's
// estimate is ~ sqrt(pi LU LV) / W sigma^2 ~ 0.03 sigma^2 on 256^2 with LU = 8, LV = 4 px).
TEST(EllipticalSynthesis, GaussianAcvFollowsTheLayAngle) {
    const double lu = 8.0, lv = 4.0, angle = 30.0 * kPi / 180.0;
    const ss::EllipticalStatistics stats(std::make_shared<ss::GaussianAcv>(1.0, lu), lv, angle);
    const std::size_t n = 256;
    const double c = std::cos(angle), s = std::sin(angle);
    struct Lag {
        double u, v;
    };
    const std::vector<Lag> lags = {{4, 0}, {8, 0}, {0, 2}, {0, 4}, {6, 3}};
    std::vector<double> sums(lags.size(), 0.0);
    double variance = 0.0;
    const int maps = 4;
    for (int seed = 1; seed <= maps; ++seed) {
        const hm::HeightMap map = ss::synthesize_surface(stats, {n, n, 1.0}, static_cast<std::uint64_t>(seed));
        for (std::size_t i = 0; i < lags.size(); ++i) {
            // The lag on the grid nearest to (u, v) in the lay frame; the closed form is taken at that lag.
            const auto tx = static_cast<long>(std::lround(c * lags[i].u - s * lags[i].v));
            const auto ty = static_cast<long>(std::lround(s * lags[i].u + c * lags[i].v));
            double sum = 0.0;
            for (std::size_t y = 0; y < n; ++y)
                for (std::size_t x = 0; x < n; ++x)
                    sum += map(x, y) * map((x + n + static_cast<std::size_t>(tx + static_cast<long>(n))) % n,
                                           (y + n + static_cast<std::size_t>(ty + static_cast<long>(n))) % n);
            sums[i] += sum / static_cast<double>(n * n) / maps;
        }
        double sq = 0.0;
        for (double h : map.heights()) sq += h * h;
        variance += sq / static_cast<double>(n * n) / maps;
    }
    EXPECT_NEAR(variance, 1.0, 0.05);
    for (std::size_t i = 0; i < lags.size(); ++i) {
        const auto tx = static_cast<double>(std::lround(c * lags[i].u - s * lags[i].v));
        const auto ty = static_cast<double>(std::lround(s * lags[i].u + c * lags[i].v));
        const double xu = c * tx + s * ty, xv = -s * tx + c * ty;
        const double expected = std::exp(-(xu / lu) * (xu / lu) - (xv / lv) * (xv / lv));
        EXPECT_NEAR(sums[i] / variance, expected, 0.04) << "lag u " << lags[i].u << " v " << lags[i].v;
    }
}

TEST(EllipticalFit, RecoversLengthsAngleAndGamma) {
    std::uint64_t seed = 100;
    double worst_length = 0.0, worst_angle = 0.0, worst_gamma = 0.0, worst_pull = 0.0;
    for (double ratio : {0.5, 0.2})
        for (double angle : {0.0, 30.0, 90.0, 135.0}) {
            const hm::HeightMap map = ss::synthesize_surface(elliptical(ratio, angle), {kSize, kSize, kSpacing}, ++seed);
            const ss::EllipticalKcFit fit = fit_of(map);
            const std::string where = fmt::format("LV/LU {} A {}", ratio, angle);
            ASSERT_TRUE(fit.failure.empty()) << where << ": " << fit.failure;
            EXPECT_EQ(fit.window, ss::Window::rectangular);
            EXPECT_TRUE(fit.anisotropic()) << where;
            const double du = fit.corr_length_u_um / kLengthU - 1.0, dv = fit.corr_length_v_um / (ratio * kLengthU) - 1.0;
            const double da = angle_difference(fit.lay_angle_deg, angle), dg = fit.gamma - kGamma;
            fmt::print("{}: LU {:.4g} +- {:.2g}, LV {:.4g} +- {:.2g}, A {:.3g} +- {:.2g}, gamma {:.4g} +- {:.2g}, "
                       "sigma {:.4g} +- {:.2g}, misfit {:.3g} floor {:.3g}, chi2 {:.3g}\n",
                       where, fit.corr_length_u_um, fit.corr_length_u_error_um, fit.corr_length_v_um,
                       fit.corr_length_v_error_um, fit.lay_angle_deg, fit.lay_angle_error_deg, fit.gamma,
                       fit.gamma_error, fit.sigma_h_um, fit.sigma_h_error_um, fit.log_residual_rms,
                       fit.statistical_floor, fit.anisotropy_chi2);
            // Within 4 standard errors of the truth ...
            EXPECT_LT(std::abs(du) * kLengthU, 4.0 * fit.corr_length_u_error_um) << where;
            EXPECT_LT(std::abs(dv) * ratio * kLengthU, 4.0 * fit.corr_length_v_error_um) << where;
            EXPECT_LT(std::abs(da), 4.0 * fit.lay_angle_error_deg) << where;
            EXPECT_LT(std::abs(dg), 4.0 * fit.gamma_error) << where;
            EXPECT_LT(std::abs(fit.sigma_h_um - kSigma), 4.0 * fit.sigma_h_error_um) << where;
            // ... and the misfit at the statistical floor (a correct model).
            EXPECT_LT(fit.log_residual_rms, 1.2 * fit.statistical_floor) << where;
            worst_length = std::max({worst_length, std::abs(du), std::abs(dv)});
            worst_angle = std::max(worst_angle, std::abs(da));
            worst_gamma = std::max(worst_gamma, std::abs(dg));
            worst_pull = std::max({worst_pull, std::abs(du) * kLengthU / fit.corr_length_u_error_um,
                                   std::abs(dv) * ratio * kLengthU / fit.corr_length_v_error_um,
                                   std::abs(da) / fit.lay_angle_error_deg, std::abs(dg) / fit.gamma_error});
        }
    fmt::print("worst: lengths {:.3g}, angle {:.3g} deg, gamma {:.3g}, pull {:.3g}\n", worst_length, worst_angle,
               worst_gamma, worst_pull);
    // The accuracy elliptical_fit.hpp states.
    EXPECT_LT(worst_length, 0.06);
    EXPECT_LT(worst_angle, 1.0);
    EXPECT_LT(worst_gamma, 0.1);
}

TEST(EllipticalFit, TurnedMapTurnsTheLay) {
    for (double angle : {30.0, 135.0}) {
        const hm::HeightMap map = ss::synthesize_surface(elliptical(0.5, angle), {kSize, kSize, kSpacing}, 3);
        const ss::EllipticalKcFit fit = fit_of(map), turned_fit = fit_of(turned(map));
        EXPECT_NEAR(angle_difference(turned_fit.lay_angle_deg, fit.lay_angle_deg + 90.0), 0.0, 0.5) << angle;
        EXPECT_NEAR(turned_fit.corr_length_u_um / fit.corr_length_u_um, 1.0, 0.01) << angle;
        EXPECT_NEAR(turned_fit.corr_length_v_um / fit.corr_length_v_um, 1.0, 0.01) << angle;
    }
}

TEST(EllipticalFit, IsotropicMapIsNotSignificant) {
    int significant = 0;
    for (std::uint64_t seed : {21u, 22u, 23u, 24u}) {
        const hm::HeightMap map = ss::synthesize_surface(elliptical(1.0, 0.0), {kSize, kSize, kSpacing}, seed);
        const ss::SurfaceFit fit = ss::fit_surface(map);
        const ss::EllipticalKcFit& e = fit.elliptical;
        ASSERT_TRUE(e.failure.empty()) << e.failure;
        fmt::print("isotropic seed {}: LV/LU {:.4g} +- {:.2g}, chi2 {:.3g}, A {:.3g} +- {:.3g}\n", seed, e.axis_ratio(),
                   e.axis_ratio_error, e.anisotropy_chi2, e.lay_angle_deg, e.lay_angle_error_deg);
        EXPECT_LT(1.0 - e.axis_ratio(), 4.0 * e.axis_ratio_error) << seed;
        significant += e.anisotropic() ? 1 : 0;
        // The geometric mean length and gamma agree with the isotropic fit's within the errors.
        EXPECT_NEAR(std::sqrt(e.corr_length_u_um * e.corr_length_v_um) / fit.kc.corr_length_um, 1.0, 0.05);
        EXPECT_NEAR(e.gamma, fit.kc.gamma, 4.0 * e.gamma_error);
    }
    EXPECT_EQ(significant, 0);
}

TEST(EllipticalFit, RefusesAMapWithoutAKneeAlongTheLay) {
    // LU = 400 um on a 128 um map: along the lay the band holds only the tail.
    const ss::EllipticalStatistics stats(std::make_shared<ss::KCorrelation>(kSigma, 400.0, kGamma), 2.0, 0.5);
    const hm::HeightMap map = ss::synthesize_surface(stats, {128, 128, kSpacing}, 5);
    const ss::EllipticalKcFit fit = fit_of(map);
    ASSERT_FALSE(fit.failure.empty());
    EXPECT_NE(fit.failure.find("LU (along the lay)"), std::string::npos) << fit.failure;
    EXPECT_THROW(ss::require_resolved(fit), surfscatter::Error);
}

TEST(EllipticalFit, ResultIsTheModelsStatistics) {
    const hm::HeightMap map = ss::synthesize_surface(elliptical(0.5, 30.0), {kSize, kSize, kSpacing}, 9);
    const ss::EllipticalKcFit fit = fit_of(map);
    const ss::EllipticalStatistics stats = fit.statistics();
    EXPECT_DOUBLE_EQ(stats.corr_length_u(), fit.corr_length_u_um);
    EXPECT_DOUBLE_EQ(stats.corr_length_v(), fit.corr_length_v_um);
    EXPECT_NEAR(stats.lay_angle() * 180.0 / kPi, fit.lay_angle_deg, 1e-12);
    EXPECT_DOUBLE_EQ(stats.sigma_h(), fit.sigma_h_um);
}

// The real instrument files: the fit runs and either resolves (finite values inside the box, errors > 0) or refuses
// with its message; what they give is printed (docs/HEIGHTMAPS.md quotes it).
TEST(EllipticalFit, RealFilesResolveOrSayWhy) {
    for (const char* name : {"di-1.di", "metropro-1.dat", "opd-1.opd"}) {
        const auto path = std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name;
        const ss::EllipticalKcFit fit = ss::fit_surface(hm::read_height_map(path, std::nullopt, std::nullopt)).elliptical;
        if (!fit.failure.empty()) {
            fmt::print("{}: {}\n", name, fit.failure);
            EXPECT_EQ(fit.failure.rfind("elliptical KC fit: ", 0), 0u) << fit.failure;
            EXPECT_THROW(ss::require_resolved(fit), surfscatter::Error);
            continue;
        }
        fmt::print("{}: LU {:.4g} +- {:.2g} um, LV {:.4g} +- {:.2g} um, A {:.4g} +- {:.2g} deg, gamma {:.4g}, anisotropy "
                   "chi2 {:.3g}, misfit {:.3g} floor {:.3g}\n",
                   name, fit.corr_length_u_um, fit.corr_length_u_error_um, fit.corr_length_v_um,
                   fit.corr_length_v_error_um, fit.lay_angle_deg, fit.lay_angle_error_deg, fit.gamma,
                   fit.anisotropy_chi2, fit.log_residual_rms, fit.statistical_floor);
        EXPECT_GE(fit.corr_length_u_um, fit.corr_length_v_um);
        EXPECT_GT(fit.corr_length_v_error_um, 0.0);
        EXPECT_GE(fit.lay_angle_deg, 0.0);
        EXPECT_LT(fit.lay_angle_deg, 180.0);
        EXPECT_TRUE(std::isfinite(fit.anisotropy_chi2));
    }
}

TEST(EllipticalFit, TooSmallAMapIsRefusedWithoutFailingTheIsotropicFit) {
    // 48^2: the isotropic fit has its 8 rings (4 to 12), the 2-D fit fewer than 16 cells; fit_surface still returns.
    const ss::KCorrelation kc(kSigma, 1.0, kGamma);
    const ss::SurfaceFit fit = ss::fit_surface(ss::synthesize_surface(kc, {48, 48, 0.25}, 3));
    EXPECT_GE(fit.kc.rings, 8u);
    EXPECT_NE(fit.elliptical.failure.find("too small"), std::string::npos) << fit.elliptical.failure;
    EXPECT_EQ(fit.elliptical.corr_length_u_um, fit.kc.corr_length_um);
    EXPECT_THROW(ss::require_resolved(fit.elliptical), surfscatter::Error);
}
