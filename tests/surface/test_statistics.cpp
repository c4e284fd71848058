// Closed forms of the KC and Gaussian models (THEORY.md 2.1-2.2, 4.1, 3.2), ABC conversion, numerically defined
// statistics (tabulated, filtered), relevant roughness against 2-D brute force, and the self-convolution refit (2.4).
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/refit.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"

namespace surfscatter::surface {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double mass_by_quadrature(const RadialStatistics& s) {
    return math::integrate_adaptive(
        [&](double y) {
            const double z = std::exp(y);
            return 2.0 * M_PI * z * z * s.psd_unit(z);
        },
        -40.0, 60.0, 1e-12);
}

TEST(KCorrelation, UnitMassCdfAndInverse) {
    for (double gamma : {1.5, 2.0, 3.0, 4.0, 7.0}) {
        const KCorrelation kc(1.3, 0.8, gamma);
        EXPECT_NEAR(mass_by_quadrature(kc), 1.0, 1e-9) << gamma;
        for (double z : {1e-3, 0.1, 1.0, 10.0, 1e3}) {
            const double cdf = math::integrate_adaptive([&](double t) { return 2.0 * M_PI * t * kc.psd_unit(t); }, 0.0, z, 1e-13);
            EXPECT_NEAR(kc.radial_cdf(z), cdf, 1e-11) << gamma << " " << z;
            if (kc.radial_cdf(z) < 1.0 - 1e-6) { EXPECT_NEAR(kc.inverse_radial_cdf(kc.radial_cdf(z)), z, 1e-9 * z); }
        }
        EXPECT_EQ(kc.inverse_radial_cdf(0.0), 0.0);
        EXPECT_TRUE(std::isinf(kc.inverse_radial_cdf(1.0)));
        EXPECT_NEAR(kc.psd(0.0), 1.3 * 1.3 * (gamma - 1.0) * 0.64 / (2.0 * M_PI), 1e-15);
    }
}

TEST(KCorrelation, MaternAcvClosedForms) {
    const double l = 2.0;
    for (double x : {1e-12, 1e-9, 1e-6, 0.01, 0.5, 1.0, 3.0, 20.0}) {
        // Elementary forms (gamma = 2, 4) against the general Bessel path (gamma = 2 + tiny, 4 + tiny).
        EXPECT_NEAR(KCorrelation(1, l, 2.0).acv_normalized(x * l), std::exp(-x), 1e-15);
        EXPECT_NEAR(KCorrelation(1, l, 4.0).acv_normalized(x * l), (1 + x) * std::exp(-x), 1e-15);
        EXPECT_NEAR(KCorrelation(1, l, 2.0 + 1e-12).acv_normalized(x * l), std::exp(-x), 1e-9) << x;
        EXPECT_NEAR(KCorrelation(1, l, 4.0 + 1e-12).acv_normalized(x * l), (1 + x) * std::exp(-x), 1e-9) << x;
        EXPECT_NEAR(KCorrelation(1, l, 3.0).acv_normalized(x * l), x * std::cyl_bessel_k(1.0, x), 1e-12) << x;
    }
    // r -> 0: C(0) = sigma^2 for every gamma, continuous through the small-r expansion.
    for (double gamma : {1.2, 1.5, 2.5, 3.0, 3.5, 5.0}) {
        const KCorrelation kc(1.7, 1.0, gamma);
        EXPECT_DOUBLE_EQ(kc.acv(0.0), 1.7 * 1.7);
        // Continuity where the small-r expansion takes over from the Bessel function (x = 1e-8).
        EXPECT_NEAR(kc.acv_normalized(1e-8 * (1 - 1e-9)), kc.acv_normalized(1e-8 * (1 + 1e-9)), 1e-11) << gamma;
        // Leading behaviour 1 - rho ~ Gamma(1-nu)/Gamma(1+nu) (x/2)^{2 nu} for nu < 1 (THEORY.md 1.5).
        const double nu = 0.5 * (gamma - 1.0);
        if (nu < 1.0) {
            const double x = 1e-9;
            const double expected = std::tgamma(1 - nu) / std::tgamma(1 + nu) * std::pow(x / 2, 2 * nu);
            EXPECT_NEAR(1.0 - kc.acv_normalized(x), expected, 1e-3 * expected + 3e-16) << gamma;
        }
    }
    // Matern rho integrates (2-D) to 2 pi P-hat(0) L^0: int rho 2 pi r dr = (2 pi)^2 P-hat(0).
    for (double gamma : {1.5, 2.5, 3.0}) {
        const KCorrelation kc(1.0, 1.0, gamma);
        const double integral = math::integrate_adaptive(
            [&](double y) { const double r = std::exp(y); return 2.0 * M_PI * r * r * kc.acv_normalized(r); },
            -30.0, 6.5, 1e-12);
        EXPECT_NEAR(integral, 4.0 * M_PI * M_PI * kc.psd_unit(0.0), 1e-8) << gamma;
    }
}

TEST(KCorrelation, BadParametersThrow) {
    EXPECT_THROW(KCorrelation(1, 1, 1.0), Error);
    EXPECT_THROW(KCorrelation(1, 1, 0.5), Error);
    EXPECT_THROW(KCorrelation(0, 1, 3), Error);
    EXPECT_THROW(KCorrelation(1, -1, 3), Error);
    EXPECT_THROW(KCorrelation(1, 1, std::nan("")), Error);
    EXPECT_THROW(GaussianAcv(1, 0), Error);
}

TEST(KCorrelation, AbcRoundTripAndCyclicPsd) {
    const KCorrelation kc(0.02, 1.5, 2.7);
    const AbcParameters abc = to_abc(kc);
    const KCorrelation back = from_abc(abc);
    EXPECT_NEAR(back.sigma_h(), 0.02, 1e-15);
    EXPECT_NEAR(back.correlation_length(), 1.5, 1e-14);
    EXPECT_DOUBLE_EQ(back.gamma(), 2.7);
    for (double f : {0.0, 0.05, 0.3, 2.0}) {
        const double cyclic = abc.a * std::pow(1.0 + abc.b * abc.b * f * f, -(abc.c + 1.0) / 2.0);
        EXPECT_NEAR(cyclic_psd_from_angular(kc.psd(2.0 * M_PI * f)), cyclic, 1e-12 * cyclic);
        EXPECT_NEAR(angular_psd_from_cyclic(cyclic), kc.psd(2.0 * M_PI * f), 1e-12 * cyclic);
    }
}

TEST(GaussianAcv, ClosedForms) {
    const GaussianAcv g(2.27, 20.9);
    EXPECT_NEAR(mass_by_quadrature(g), 1.0, 1e-10);
    EXPECT_NEAR(g.acv(0.0), 2.27 * 2.27, 1e-14);
    // THEORY.md 1.6a: PSD_f = pi l^2 sigma^2 exp(-(pi l f)^2).
    for (double f : {0.0, 0.01, 0.03}) {
        const double expected = M_PI * 20.9 * 20.9 * 2.27 * 2.27 * std::exp(-std::pow(M_PI * 20.9 * f, 2));
        EXPECT_NEAR(cyclic_psd_from_angular(g.psd(2.0 * M_PI * f)), expected, 1e-10 * expected);
    }
    EXPECT_NEAR(g.inverse_radial_cdf(g.radial_cdf(0.07)), 0.07, 1e-12);
    EXPECT_NEAR(g.mean_square_slope(0.0, kInf), 4.0 * 2.27 * 2.27 / (20.9 * 20.9), 1e-14);
    // Smoothing and cutoff against the generic quadrature of the base class.
    const double s = 3.0, zc = 0.08;
    EXPECT_NEAR(g.mean_square_slope(s, zc), g.RadialStatistics::mean_square_slope(s, zc), 1e-9 * g.mean_square_slope(s, zc));
}

TEST(Slopes, TheoryReferenceValues) {
    // THEORY.md 4.1 (L = 1, sigma = 1).
    EXPECT_NEAR(KCorrelation(1, 1, 3.0).mean_square_slope(0.05, kInf), 4.4439, 1e-4);
    EXPECT_NEAR(KCorrelation(1, 1, 3.0).mean_square_slope(0.3, kInf), 1.2884, 1e-4);
    EXPECT_NEAR(KCorrelation(1, 1, 2.5).mean_square_slope(0.05, kInf), 8.2157, 1e-4);
    EXPECT_NEAR(KCorrelation(1, 1, 4.0).mean_square_slope(0.3, kInf), 0.9379, 1e-4);
    // Unfiltered: 2 sigma^2 / ((gamma - 3) L^2), infinite for gamma <= 3.
    EXPECT_NEAR(KCorrelation(0.5, 2.0, 4.5).mean_square_slope(0.0, kInf), 2 * 0.25 / (1.5 * 4.0), 1e-14);
    EXPECT_TRUE(std::isinf(KCorrelation(1, 1, 3.0).mean_square_slope(0.0, kInf)));
    EXPECT_TRUE(std::isinf(KCorrelation(1, 1, 2.0).RadialStatistics::mean_square_slope(0.0, kInf)));
    // THEORY.md 3.2 sharp cutoff, gamma = 3: sigma^2/L^2 [ln(1+u) - u/(1+u)], u = L^2 zeta_c^2.
    for (double zc : {0.1, 1.0, 37.0}) {
        const double l = 0.7, sigma = 0.3, u = l * l * zc * zc;
        const double expected = sigma * sigma / (l * l) * (std::log1p(u) - u / (1 + u));
        EXPECT_NEAR(KCorrelation(sigma, l, 3.0).mean_square_slope(0.0, zc), expected, 1e-12 * expected);
    }
    // Closed forms against the generic quadrature.
    for (double gamma : {2.2, 3.0, 3.7}) {
        const KCorrelation kc(1.0, 1.0, gamma);
        for (auto [s, zc] : {std::pair{0.05, kInf}, std::pair{0.0, 20.0}, std::pair{0.2, 5.0}}) {
            const double closed = kc.mean_square_slope(s, zc), numeric = kc.RadialStatistics::mean_square_slope(s, zc);
            EXPECT_NEAR(closed, numeric, 1e-8 * closed) << gamma << " " << s << " " << zc;
        }
    }
}

// Brute-force M_disc: 2-D midpoint rule over the shifted disc in polar coordinates about its centre.
double disc_mass_brute_force(const RadialStatistics& s, double theta, double lambda_nm) {
    const double k = wavenumber_per_um(lambda_nm), c = k * std::sin(theta);
    const int nr = 4000, nphi = 512;
    double sum = 0.0;
    for (int i = 0; i < nr; ++i) {
        // Radius grid graded towards the origin of the zeta plane is not aligned with the disc: use many points.
        const double rho = k * (i + 0.5) / nr;
        for (int j = 0; j < nphi; ++j) {
            const double phi = 2.0 * M_PI * (j + 0.5) / nphi;
            const double zx = c + rho * std::cos(phi), zy = rho * std::sin(phi);
            sum += s.psd_unit(std::hypot(zx, zy)) * rho;
        }
    }
    return sum * (k / nr) * (2.0 * M_PI / nphi);
}

TEST(RelevantRoughness, DiscMassAgainstBruteForce) {
    const KCorrelation kc(1.0, 0.5, 3.0);
    const GaussianAcv gauss(2.27, 20.9);
    for (double theta_deg : {0.0, 20.0, 60.0, 85.0}) {
        const double t = theta_deg * M_PI / 180.0;
        EXPECT_NEAR(visible_disc_mass(kc, t, 550.0), disc_mass_brute_force(kc, t, 550.0), 2e-5) << theta_deg;
        EXPECT_NEAR(visible_disc_mass(gauss, t, 10600.0), disc_mass_brute_force(gauss, t, 10600.0), 2e-5) << theta_deg;
    }
    // THEORY.md 1.6a relevant roughness (Gaussian case): 2.2700, 2.2687, 2.1136, 1.8727 um.
    const double expected[] = {2.2700, 2.2687, 2.1136, 1.8727};
    const double angles[] = {20, 40, 60, 70};
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(relevant_roughness(gauss, angles[i] * M_PI / 180.0, 10600.0), expected[i], 6e-5) << angles[i];
    // Normal incidence: M_disc is the radial CDF at k; total integrated scatter.
    EXPECT_NEAR(visible_disc_mass(kc, 0.0, 550.0), kc.radial_cdf(wavenumber_per_um(550.0)), 1e-15);
    const double sr = relevant_roughness(kc, 0.0, 550.0);
    EXPECT_NEAR(kc.total_integrated_scatter(0.0, 550.0), 1.0 - std::exp(-std::pow(4 * M_PI * sr / 0.55, 2)), 1e-14);
}

TEST(NumericalStatistics, TabulatedKcReproducesClosedForms) {
    const KCorrelation kc(0.05, 1.2, 3.0);
    std::vector<double> z, p;
    for (int i = 0; i <= 1600; ++i) {
        z.push_back(1e-4 * std::pow(10.0, i / 200.0));
        p.push_back(kc.psd(z.back()));
    }
    const TabulatedPsd tab(z, p);
    EXPECT_NEAR(tab.sigma_h(), 0.05, 1e-6);
    for (double r : {0.0, 0.01, 0.3, 1.0, 4.0, 15.0})
        EXPECT_NEAR(tab.acv_normalized(r), kc.acv_normalized(r), 2e-5) << r;
    for (double zeta : {0.01, 0.5, 3.0, 100.0})
        EXPECT_NEAR(tab.radial_cdf(zeta), kc.radial_cdf(zeta), 2e-5) << zeta;
    EXPECT_THROW(TabulatedPsd({1, 2, 3, 4}, {1, 1, 1, 1}), Error);       // tail too flat: infinite sigma
    EXPECT_THROW(TabulatedPsd({1, 2, 2, 4}, {1, 0.1, 0.01, 0.001}), Error);  // not increasing
    EXPECT_THROW(TabulatedPsd({1, 2, 3, 4}, {1, -1, 0.01, 0.001}), Error);
}

TEST(PsdSplit, MacroMicroPartsAddUp) {
    auto kc = std::make_shared<KCorrelation>(0.1, 2.0, 3.0);
    const double zc = cutoff_frequency(550.0, 100.0);
    EXPECT_NEAR(zc, wavenumber_per_um(550.0) / 100.0, 1e-14);
    for (LowPassFilter f : {LowPassFilter::sharp, LowPassFilter::iso_gaussian}) {
        const PsdSplit split = split_psd(kc, zc, f);
        EXPECT_NEAR(split.sigma2_macro + split.sigma2_micro, 0.01, 1e-15);
        EXPECT_NEAR(split.micro->sigma_h() * split.micro->sigma_h(), split.sigma2_micro, 1e-6 * split.sigma2_micro);
        EXPECT_GT(split.slope2_macro, 0.0);
        // Micro part: the transfer applied to the PSD, unit mass renormalised.
        const double z = 3.0 * zc;
        EXPECT_NEAR(split.micro->psd(z), kc->psd(z) * (1.0 - low_pass_transfer(f, z, zc)), 1e-9 * kc->psd(z));
    }
    const PsdSplit sharp = split_psd(kc, zc, LowPassFilter::sharp);
    const double u = 4.0 * zc * zc;
    EXPECT_NEAR(sharp.slope2_macro, 0.01 / 4.0 * (std::log1p(u) - u / (1 + u)), 1e-12);
    EXPECT_NEAR(low_pass_transfer(LowPassFilter::iso_gaussian, zc, zc), 0.25, 1e-15);  // 50 % amplitude
}

TEST(Refit, Gamma2IsExactAndTheoryExponents) {
    const RefitResult r2 = refit_self_convolutions(KCorrelation(1.0, 1.0, 2.0), 13);
    EXPECT_NEAR(r2.exponent_x, 1.0, 1e-6);
    for (int m = 1; m <= 13; ++m) {
        EXPECT_NEAR(r2.corr_length_m[m - 1], 1.0 / m, 1e-6 / m);
        EXPECT_LT(r2.misfit_m[m - 1], 1e-5);
    }
    const RefitResult r3 = refit_self_convolutions(KCorrelation(1.0, 1.0, 3.0), 13);
    std::printf("refit gamma=3: x = %.4f, L_m: %.3f %.3f %.3f %.3f %.3f misfit m=2 %.3f m=5 %.3f\n", r3.exponent_x,
                r3.corr_length_m[1], r3.corr_length_m[2], r3.corr_length_m[4], r3.corr_length_m[7], r3.corr_length_m[12],
                r3.misfit_m[1], r3.misfit_m[4]);
    for (double gamma : {2.5, 4.0}) {
        const RefitResult r = refit_self_convolutions(KCorrelation(1.0, 1.0, gamma), 13);
        std::printf("refit gamma=%.1f: x = %.4f\n", gamma, r.exponent_x);
    }
}

}  // namespace
}  // namespace surfscatter::surface
