// Profiles (surface/profile_statistics.hpp): the KC's profile PSD against a quadrature of its 2-D PSD written here,
// and the KC fit to a profile's 1-D PSD recovering the statistics of synthesised KC profiles.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "surfscatter/heightmap/line_scan.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/profile_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/scatter_lobe_table.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::surface {
namespace {

// The integral of f over the real line by the trapezoid rule after zeta_y = c sinh t (f algebraic: the integrand
// in t decays exponentially, and the rule converges exponentially in the step).
// (step and end in t: the defaults reach 1e-9 for gamma down to 1.3; the marginal of gamma 3 needs far less).
template <typename F>
double integral_over_line(F f, double c, double step = 1e-3, double end = 100.0) {
    double sum = 0.0;
    for (double t = -end; t <= end; t += step) sum += f(c * std::sinh(t)) * c * std::cosh(t);
    return sum * step;
}

// P1(zeta_x) = integral of P-hat(sqrt(zeta_x^2 + zeta_y^2)) d zeta_y, to 1e-9 relative, and it has unit mass.
TEST(ProfileStatistics, KcProfilePsdIsTheTwoDimensionalPsdIntegratedAcross) {
    for (double gamma : {1.3, 2.0, 3.7, 8.0})
        for (double zeta : {0.0, 0.05, 0.4, 3.0, 40.0}) {
            const KCorrelation kc(1.0, 2.5, gamma);
            const double quadrature =
                integral_over_line([&](double zy) { return kc.psd_unit(std::hypot(zeta, zy)); }, std::hypot(zeta, 0.4));
            EXPECT_NEAR(kc.profile_psd_unit(zeta) / quadrature, 1.0, 1e-9) << "gamma " << gamma << " zeta " << zeta;
        }
    for (double gamma : {1.3, 3.7}) {
        const KCorrelation kc(1.0, 2.5, gamma);
        EXPECT_NEAR(integral_over_line([&](double z) { return kc.profile_psd_unit(z); }, 0.4), 1.0, 1e-9) << gamma;
    }
}

// Forty synthesised KC profiles of 8192 points (sigma_h 0.1 um, L_c 5 um, gamma 3; 4096 um long, 0.5 um apart): the
// fit of the KC's profile PSD to each profile's 1-D PSD recovers the statistics. Measured: mean sigma_h 0.10122 um,
// L_c 5.101 um, gamma 2.994 (per profile sd about 3.5 %, 10 %, 0.09); the test allows 2 %, 4 % and 0.05 on the mean
// and about 4 sd per profile. Fitting the 2-D KC's shape instead would read gamma 1 low (the profile PSD falls as
// zeta^-gamma, the 2-D one as zeta^-(gamma+1)).
TEST(ProfileStatistics, FitRecoversSynthesisedKcProfiles) {
    const KCorrelation truth(0.1, 5.0, 3.0);
    double sigma = 0, length = 0, gamma = 0;
    constexpr int kSeeds = 40;
    for (int seed = 1; seed <= kSeeds; ++seed) {
        heightmap::LineScan scan;
        scan.spacing_um = 0.5;
        scan.heights_um = synthesize_profile(truth, 8192, 0.5, static_cast<std::uint64_t>(seed));
        scan.origin = "synthesised";
        const ProfileFit fit = fit_profile(scan);
        ASSERT_TRUE(fit.kc.failure.empty()) << fit.kc.failure;
        EXPECT_NEAR(fit.kc.sigma_h_um, 0.1, 0.014) << seed;
        EXPECT_NEAR(fit.kc.corr_length_um, 5.0, 2.0) << seed;
        EXPECT_NEAR(fit.kc.gamma, 3.0, 0.4) << seed;
        EXPECT_LT(fit.kc.log_residual_rms, kPoorFitFactor * fit.kc.statistical_floor) << seed;
        sigma += fit.kc.sigma_h_um / kSeeds, length += fit.kc.corr_length_um / kSeeds, gamma += fit.kc.gamma / kSeeds;
    }
    EXPECT_NEAR(sigma, 0.1, 0.002);
    EXPECT_NEAR(length, 5.0, 0.2);
    EXPECT_NEAR(gamma, 3.0, 0.05);
    std::printf("mean over %d profiles: sigma_h %.5f um, L_c %.4f um, gamma %.4f\n", kSeeds, sigma, length, gamma);
}

// The KC 2-D PSD written here: sigma^2 (gamma - 1) L^2 / (2 pi) (1 + L^2 z^2)^(-(gamma + 1) / 2).
double kc_psd(double sigma, double length, double gamma, double z) {
    return sigma * sigma * (gamma - 1) * length * length / (2 * kPi) * std::pow(1 + length * length * z * z, -(gamma + 1) / 2);
}

// The KC profile PSD written here (THEORY.md 2.1): sigma^2 (gamma - 1) L B / (2 pi) (1 + L^2 u^2)^(-gamma / 2),
// B = sqrt(pi) Gamma(gamma / 2) / Gamma((gamma + 1) / 2): the 2-D PSD above integrated across the line (the first
// test checks the library's against that quadrature).
double kc_profile_psd(double sigma, double length, double gamma, double u) {
    const double b = std::sqrt(kPi) * std::exp(std::lgamma(gamma / 2) - std::lgamma((gamma + 1) / 2));
    return sigma * sigma * (gamma - 1) * length * b / (2 * kPi) * std::pow(1 + length * length * u * u, -gamma / 2);
}

// A profile's periodogram without scatter: P1 at the bins of n points dx apart, its rms the bins' own.
ProfilePeriodogram kc_periodogram(double sigma, double length, double gamma, std::size_t n, double dx) {
    ProfilePeriodogram p;
    p.dzeta = 2 * kPi / (static_cast<double>(n) * dx);
    p.points = n;
    p.origin = "KC";
    for (std::size_t k = 0; k <= n / 2; ++k)
        p.psd.push_back(kc_profile_psd(sigma, length, gamma, static_cast<double>(k) * p.dzeta));
    p.rms_um = std::sqrt(p.sum());
    return p;
}

// A synthesised KC profile (sigma_h 0.1 um, L_c 5 um, gamma 3; 8192 points 0.5 um apart, plane removed), as the
// measured route's tests below read it.
heightmap::LineScan kc_scan(const KCorrelation& kc, std::uint64_t seed) {
    heightmap::LineScan scan;
    scan.spacing_um = 0.5;
    scan.origin = "synthesised";
    scan.heights_um = synthesize_profile(kc, 8192, 0.5, seed);
    return scan;
}
constexpr int kProfileSeeds = 16;

// The step before the transform: the Hann periodogram of synthesised KC profiles (profile_periodogram, as measured:
// no window correction) has the KC's 1-D marginal, the quadrature across the 2-D closed form written here, as its
// mean, in octaves of bins 8 .. 4095 (two-sided per unit zeta_x: the synthesis' and the periodogram's conventions
// agree), and the profiles' variance is the marginal's sum over the synthesised lines. Over 16 profiles: measured
// octave ratios 0.97-1.03 (standard errors 1.6-8 %); the test allows 4 standard errors (Hann bins correlate: 1.56 x
// the variance of independent ones) plus 2 % (the window's leakage, the removed line), and 4 standard errors of the
// mean variance.
TEST(ProfileStatistics, SynthesisedProfilesHaveTheKcMarginalAsTheirPeriodogram) {
    const double sigma = 0.1, length = 5.0, gamma = 3.0;
    const KCorrelation kc(sigma, length, gamma);
    const auto marginal = [&](double u) {
        return integral_over_line([&](double zy) { return kc_psd(sigma, length, gamma, std::hypot(u, zy)); },
                                  std::hypot(u, 1.0 / length), 0.02, 20.0);
    };
    std::vector<double> held(12, 0.0);
    double variance = 0.0, variance2 = 0.0, dzeta = 0.0;
    for (int seed = 1; seed <= kProfileSeeds; ++seed) {
        const ProfilePeriodogram p = profile_periodogram(kc_scan(kc, static_cast<std::uint64_t>(seed)), heightmap::Form::plane);
        dzeta = p.dzeta;
        for (std::size_t k = 8; k < 4096; ++k) held[static_cast<std::size_t>(std::log2(static_cast<double>(k)))] += p.psd[k];
        variance += p.rms_um * p.rms_um / kProfileSeeds;
        variance2 += std::pow(p.rms_um, 4) / kProfileSeeds;
    }
    for (std::size_t octave = 3; octave < 12; ++octave) {
        const std::size_t first = std::size_t{1} << octave;
        double truth = 0.0;
        for (std::size_t k = first; k < 2 * first; ++k) truth += marginal(static_cast<double>(k) * dzeta);
        const double ratio = held[octave] / kProfileSeeds / truth;
        const double error = std::sqrt(1.56 / (kProfileSeeds * static_cast<double>(first)));
        EXPECT_NEAR(ratio, 1.0, 4 * error + 0.02) << "octave from bin " << first;
        std::printf("bins %zu-%zu: mean periodogram / KC marginal %.4f (standard error %.3f)\n", first, 2 * first - 1,
                    ratio, error);
    }
    double lines = 0.0;
    for (std::size_t k = 1; k <= 4096; ++k) lines += (k == 4096 ? 1.0 : 2.0) * marginal(static_cast<double>(k) * dzeta) * dzeta;
    const double error = std::sqrt((variance2 - variance * variance) / (kProfileSeeds - 1));
    EXPECT_NEAR(variance, lines, 4 * error);
    std::printf("profile variance %.6g um^2 (standard error %.2g), the synthesised lines' %.6g, sigma_h^2 %.6g\n",
                variance, error, lines, sigma * sigma);
}

// The KC's exact profile PSD (sampled at the bins of a 4096-point profile 0.5 um apart, L 5 um: no noise) gives back
// its 2-D PSD (closed form above). The fit's forward transform (fitted_profile_psd) is the quadrature across its own
// P written here (the transform's constant) to 1e-6. Its P is smoothed where the data hold few bins (the prior that
// makes the fit stable on noisy spectra): measured worst relative error 0.077 (gamma 3) and 0.099 (gamma 2) from the
// 17th to the 64th bin, 0.40 and 0.45 up to the 16th (knots an octave apart there), 0.028 and 0.018 above the 64th;
// the test allows 0.12, 0.6 and 0.03. Those lowest bins hold little variance: the band scale (sigma_h made the
// profile's rms) is 0.998 and 1.011 (for gamma 2 the profile's bins hold 1 % more than the disc |zeta| <= Nyquist).
// The GHS lobe at g 4.26 (as below) is within 0.01 of the KC's from 0.2 to 4 rad/um for gamma 3 (measured 0.7 %);
// for gamma 2 it reads 1.09-1.17 x the KC's: that KC holds 3 % of sigma^2 beyond Nyquist, whose orders widen its
// lobe, and a profile sampled 0.5 um apart does not hold it (the band limit, as for a map; printed, not tested).
TEST(ProfileStatistics, ExactKcProfilePsdGivesTheKcTwoDimensionalPsd) {
    for (double gamma : {2.0, 3.0}) {
        const double sigma = 0.1, length = 5.0, dx = 0.5;
        const auto s = std::make_shared<const ProfileStatistics>(kc_periodogram(sigma, length, gamma, 4096, dx));
        EXPECT_NEAR(s->window_scale(), 1.0, 1e-12);
        double worst[3] = {0, 0, 0};
        for (std::size_t k = 1; k <= 2048; ++k) {
            const double z = static_cast<double>(k) * s->ring_width();
            double& w = worst[k <= 16 ? 0 : k <= 64 ? 1 : 2];
            w = std::max(w, std::abs(s->psd(z) / kc_psd(sigma, length, gamma, z) - 1));
        }
        EXPECT_LT(worst[0], 0.6) << gamma;
        EXPECT_LT(worst[1], 0.12) << gamma;
        EXPECT_LT(worst[2], 0.03) << gamma;
        EXPECT_NEAR(s->sigma_h() / s->map_rms(), 1.0, 1e-9) << gamma;
        EXPECT_NEAR(s->band_scale(), 1.0, 0.02) << gamma;
        for (double u : {0.0, 0.01, 0.3, 2.0, 6.0}) {
            const double across = integral_over_line([&](double zy) { return s->fitted_psd(std::hypot(u, zy)); },
                                                     std::max(u, 0.01), 1e-3, 40.0);
            EXPECT_NEAR(s->fitted_profile_psd(u) / across, 1.0, 1e-6) << gamma << " u " << u;
        }
        const KCorrelation kc(sigma, length, gamma);
        const double k = 2 * kPi / 0.55, g = std::pow(k * sigma * (std::cos(kPi / 6) + std::cos(kPi / 9)), 2);
        const auto lobe = ScatterLobeTable::get(s), truth = ScatterLobeTable::get(std::make_shared<const KCorrelation>(kc));
        double worst_lobe = 0;
        for (double zeta : {0.2, 0.8, 1.8, 4.0})
            worst_lobe = std::max(worst_lobe, std::abs(lobe->eval(g, zeta) / truth->eval(g, zeta) - 1));
        if (gamma == 3.0) EXPECT_LT(worst_lobe, 0.01);
        std::printf("gamma %.1f: worst relative error of P %.3g up to the 16th bin, %.3g to the 64th, %.3g above; band "
                    "scale %.5f; GHS lobe within %.3g of the KC's\n",
                    gamma, worst[0], worst[1], worst[2], s->band_scale(), worst_lobe);
    }
}

// The cause of ghs reading 0.71 of the truth on a synthesised KC profile, and its fix. The direct inverse Abel
// transform of the banded periodogram came out negative wherever the noise made P1 rise (95 of 4096 bins on seed 3);
// made positive there, it gained variance (29 %) that the band scale then took from every frequency: P 0.45 x the
// KC's at 1.8 rad/um, band scales 0.76-0.90 over 8 profiles, the GHS lobe 0.80 x the KC's there on average. The
// fitted route (profile_statistics.hpp) needs no such scale (within 5 % of 1 on every profile), and over 16 profiles
// the mean of its P and of its GHS lobe S_g (the ghs BRDF's only statistics-dependent factor but the normalisation:
// bsdf/ghs.hpp) at theta_i 30, theta_o 20 deg, 550 nm (g 4.26) follow the KC's closed form and table. Measured: mean
// P / KC 1.05, 0.97, 0.96, 1.01 and mean S_g / KC 1.04, 0.99, 0.97, 1.00 at zeta 0.2, 0.8, 1.8, 4 rad/um (per profile
// sd 5-15 %, most of it the profile's own rms: sigma_h's sampling error moves g); the test allows 3 standard errors
// of each mean and at most 10 %.
TEST(ProfileStatistics, SynthesisedProfilesGiveTheKcTwoDimensionalPsdAndGhsLobe) {
    const auto kc = std::make_shared<const KCorrelation>(0.1, 5.0, 3.0);
    const double k = 2 * kPi / 0.55, theta_i = 30 * kPi / 180, theta_o = 20 * kPi / 180;
    const double g = std::pow(k * 0.1 * (std::cos(theta_i) + std::cos(theta_o)), 2);
    const auto truth = ScatterLobeTable::get(kc);
    const std::vector<double> zetas = {0.2, 0.8, 1.8, 4.0};
    std::vector<double> psd(zetas.size()), psd2(zetas.size()), lobe(zetas.size()), lobe2(zetas.size());
    for (int seed = 1; seed <= kProfileSeeds; ++seed) {
        const auto s = std::make_shared<const ProfileStatistics>(kc_scan(*kc, static_cast<std::uint64_t>(seed)),
                                                                 heightmap::Form::plane);
        EXPECT_NEAR(s->band_scale(), 1.0, 0.05) << seed;
        EXPECT_NEAR(s->sigma_h() / s->map_rms(), 1.0, 1e-9) << seed;
        const auto table = ScatterLobeTable::get(s);
        for (std::size_t i = 0; i < zetas.size(); ++i) {
            const double p = s->psd(zetas[i]) / kc->psd(zetas[i]), l = table->eval(g, zetas[i]) / truth->eval(g, zetas[i]);
            psd[i] += p / kProfileSeeds, psd2[i] += p * p / kProfileSeeds;
            lobe[i] += l / kProfileSeeds, lobe2[i] += l * l / kProfileSeeds;
        }
    }
    const auto error = [](double mean, double mean2) { return std::sqrt((mean2 - mean * mean) / (kProfileSeeds - 1)); };
    for (std::size_t i = 0; i < zetas.size(); ++i) {
        EXPECT_NEAR(psd[i], 1.0, std::min(0.1, 3 * error(psd[i], psd2[i]))) << "P at zeta " << zetas[i];
        EXPECT_NEAR(lobe[i], 1.0, std::min(0.1, 3 * error(lobe[i], lobe2[i]))) << "S_g at zeta " << zetas[i];
        std::printf("zeta %.2g rad/um: mean P / KC %.4f (standard error %.3f), mean S_g / KC %.4f (%.3f), g %.3g\n",
                    zetas[i], psd[i], error(psd[i], psd2[i]), lobe[i], error(lobe[i], lobe2[i]), g);
    }
}

// A red spectrum (a KC whose correlation length, 2 mm, is half the profile's 4.1 mm: most of the variance in the
// first bins, as on the real profiles opdx-3 and hfm-1): the fit's variance stays the profile's within the band
// scale's stated bounds. With the model taken at each band's centre instead of its bins' mean, the lowest knots rose
// until P held 38 x hfm-1's variance (band scale 0.026). Measured over 4 profiles: band scales 0.88, 0.74, 1.06,
// 1.20 (0.07-0.34 with the model at the band centres); the test allows 0.5 .. 2.
TEST(ProfileStatistics, RedSpectrumKeepsTheProfileVariance) {
    const KCorrelation kc(0.1, 2000.0, 3.0);
    for (int seed = 1; seed <= 4; ++seed) {
        const ProfileStatistics s(kc_scan(kc, static_cast<std::uint64_t>(seed)), heightmap::Form::plane);
        EXPECT_GT(s.band_scale(), 0.5) << seed;
        EXPECT_LT(s.band_scale(), 2.0) << seed;
        std::printf("seed %d: band scale %.4f, standard error of sigma %.3g\n", seed, s.band_scale(), s.sigma_relative_error());
    }
}

// Rows of a synthesised isotropic KC map (4096 x 1024 points 0.5 um apart, L 5 um): each row's measured profile
// statistics give the map's sigma within 3 of their own standard errors (measured: within 1.1 of them, 6-7 % each),
// and the mean over 8 rows within 3 of its.
TEST(ProfileStatistics, RowsOfAnIsotropicMapGiveItsSigmaWithinTheirStandardError) {
    const KCorrelation truth(0.1, 5.0, 3.0);
    const heightmap::HeightMap map = synthesize_surface(truth, {4096, 1024, 0.5}, 7);
    double sum2 = 0;
    for (double h : map.heights()) sum2 += h * h;
    const double map_rms = std::sqrt(sum2 / static_cast<double>(map.heights().size()));
    double mean = 0, error2 = 0;
    constexpr int kRows = 8;
    for (int r = 0; r < kRows; ++r) {
        heightmap::LineScan scan;
        scan.spacing_um = 0.5;
        scan.origin = "row";
        const auto row = map.heights().begin() + static_cast<std::ptrdiff_t>(r * 128 * 4096);
        scan.heights_um.assign(row, row + 4096);
        const ProfileStatistics s(scan, heightmap::Form::plane);
        const double error = s.sigma_relative_error();
        EXPECT_GT(error, 0.005);
        EXPECT_LT(std::abs(s.sigma_h() / map_rms - 1), 3 * error) << "row " << r * 128;
        mean += s.sigma_h() / map_rms / kRows, error2 += error * error / (kRows * kRows);
        std::printf("row %d: sigma %.5f um (map %.5f um, row %.5f um), standard error %.3g, %zu knots, band scale %.4f\n", r * 128,
                    s.sigma_h(), map_rms, s.map_rms(), error, s.knots(), s.band_scale());
    }
    EXPECT_LT(std::abs(mean - 1), 3 * std::sqrt(error2));
}

}  // namespace
}  // namespace surfscatter::surface
