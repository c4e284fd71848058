// Spectral synthesis: determinism, and the estimated PSD of a synthetic surface against the closed form it was
// made from.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/psd_estimate.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter::surface;
namespace hm = surfscatter::heightmap;

TEST(HeightSynthesis, SameSeedSameSurface) {
    const ss::KCorrelation kc(0.2, 3.0, 2.5);
    const hm::HeightMap a = ss::synthesize_surface(kc, {64, 48, 0.5}, 42);
    const hm::HeightMap b = ss::synthesize_surface(kc, {64, 48, 0.5}, 42);
    const hm::HeightMap c = ss::synthesize_surface(kc, {64, 48, 0.5}, 43);
    EXPECT_EQ(a.heights(), b.heights());
    EXPECT_NE(a.heights(), c.heights());
    EXPECT_EQ(a.nx(), 64u);
    EXPECT_EQ(a.ny(), 48u);
    EXPECT_DOUBLE_EQ(a.spacing_x(), 0.5);
}

TEST(HeightSynthesis, RejectsBadGrids) {
    const ss::KCorrelation kc(0.2, 3.0, 2.5);
    EXPECT_THROW(ss::synthesize_surface(kc, {7, 64, 0.5}, 1), surfscatter::Error);
    EXPECT_THROW(ss::synthesize_surface(kc, {64, 64, 0.0}, 1), surfscatter::Error);
    EXPECT_THROW(ss::synthesize_surface(kc, {64, 64, -2.0}, 1), surfscatter::Error);
}

// The ring means of the Hann periodogram of a synthetic KC surface follow the KC PSD. Statistics: ln of a ring
// mean has variance 1/nu and mean -1/(2 nu) (effective_samples), so over a group of rings the nu-weighted mean
// of ln(ring / model) + 1/(2 nu) is 0 with standard deviation 1/sqrt(sum nu). Allowed: 4 standard deviations
// plus 1 % for the window's smoothing of the curved PSD.
TEST(HeightSynthesis, RadialPsdMatchesKcInResolvedBand) {
    for (double gamma : {2.0, 3.0, 4.0}) {
        const ss::KCorrelation kc(0.1, 2.0, gamma);  // L = 4 pixels of 0.5 um
        const hm::HeightMap map = ss::synthesize_surface(kc, {512, 512, 0.5}, 7);
        const ss::RadialPsd radial = ss::radial_average(ss::estimate_psd(map));
        // Groups of rings [4, 8), [8, 16), ..., [128, 256): plateau, knee and tail (zeta L from 0.2 to 6).
        for (std::size_t first = 4; first < 256; first *= 2) {
            double sum_nu = 0.0, sum = 0.0;
            for (std::size_t ring = first; ring < 2 * first; ++ring) {
                const std::size_t i = ring - 1;
                const double nu = ss::effective_samples(radial.window, radial.count[i]);
                sum += nu * (std::log(radial.psd[i] / kc.psd(radial.zeta[i])) + 0.5 / nu);
                sum_nu += nu;
            }
            EXPECT_LT(std::abs(sum / sum_nu), 4.0 / std::sqrt(sum_nu) + 0.01)
                << "gamma " << gamma << ", rings " << first << ".." << 2 * first - 1;
        }
    }
}

// The 1-D PSD of a cut through an isotropic surface against its closed forms (THEORY.md 2.1):
// KC: sigma^2 (gamma-1) L / (2 pi) sqrt(pi) Gamma(gamma/2) / Gamma((gamma+1)/2) (1 + L^2 zeta^2)^(-gamma/2),
// Gaussian ACV: sigma^2 l / (2 sqrt(pi)) exp(-l^2 zeta^2 / 4).
TEST(ProfileSynthesis, ProfilePsdMatchesClosedForms) {
    for (double gamma : {1.5, 2.0, 3.0, 7.0}) {
        const ss::KCorrelation kc(0.3, 2.0, gamma);
        for (double zeta : {0.0, 0.1, 1.0, 10.0, 300.0}) {
            const double expected = 0.09 * (gamma - 1) * 2.0 / (2 * M_PI) * std::sqrt(M_PI) * std::tgamma(gamma / 2) /
                                    std::tgamma((gamma + 1) / 2) * std::pow(1 + 4 * zeta * zeta, -gamma / 2);
            EXPECT_NEAR(ss::profile_psd(kc, zeta) / expected, 1.0, 1e-8) << gamma << " " << zeta;
        }
    }
    const ss::GaussianAcv gauss(0.2, 1.5);
    for (double zeta : {0.0, 0.5, 2.0, 5.0})
        EXPECT_NEAR(ss::profile_psd(gauss, zeta) / (0.04 * 1.5 / (2 * std::sqrt(M_PI)) * std::exp(-2.25 * zeta * zeta / 4)),
                    1.0, 1e-8)
            << zeta;
}

// Random profiles: deterministic per seed, zero mean (or a random one), and their mean periodogram over seeds is the 1-D PSD
// (the synthesis's variance per frequency is P1 dzeta; 400 profiles leave ~5 % noise per bin, averaged over 8 bins).
TEST(ProfileSynthesis, PeriodogramMatchesProfilePsd) {
    const ss::KCorrelation kc(0.1, 1.0, 3.0);
    const std::size_t n = 256;
    const double dx = 0.1, dzeta = 2 * M_PI / (static_cast<double>(n) * dx);
    EXPECT_EQ(ss::synthesize_profile(kc, n, dx, 5), ss::synthesize_profile(kc, n, dx, 5));
    EXPECT_NE(ss::synthesize_profile(kc, n, dx, 5), ss::synthesize_profile(kc, n, dx, 6));
    std::vector<double> power(n / 2 + 1, 0.0);
    const int seeds = 400;
    for (int s = 0; s < seeds; ++s) {
        const auto h = ss::synthesize_profile(kc, n, dx, static_cast<std::uint64_t>(s));
        double mean = 0;
        for (double v : h) mean += v;
        EXPECT_NEAR(mean / n, 0.0, 1e-12);
        for (std::size_t m = 1; m <= n / 2; ++m) {
            std::complex<double> c = 0;
            for (std::size_t j = 0; j < n; ++j) c += h[j] * std::exp(std::complex<double>(0, -2 * M_PI * static_cast<double>(m * j) / static_cast<double>(n)));
            power[m] += std::norm(c) / (n * n) / seeds;  // E|c/n|^2 = P1 dzeta
        }
    }
    for (std::size_t m = 2; m + 8 <= n / 2; m += 8) {
        double got = 0, expected = 0;
        for (std::size_t q = m; q < m + 8; ++q) {
            got += power[q];
            expected += ss::profile_psd(kc, static_cast<double>(q) * dzeta) * dzeta;
        }
        EXPECT_NEAR(got / expected, 1.0, 0.12) << "bins from " << m;
    }
    // ProfileMean::random keeps the zero-frequency line, drawn from the same noise: the same profile plus a constant,
    // of variance P1(0) dzeta over seeds (400 seeds: 7 % standard error).
    double offset_variance = 0;
    for (int s = 0; s < seeds; ++s) {
        const auto zero = ss::synthesize_profile(kc, n, dx, static_cast<std::uint64_t>(s));
        const auto random = ss::synthesize_profile(kc, n, dx, static_cast<std::uint64_t>(s), ss::ProfileMean::random);
        const double offset = random[0] - zero[0];
        for (std::size_t j = 0; j < n; ++j) ASSERT_NEAR(random[j] - zero[j], offset, 1e-12);
        offset_variance += offset * offset / seeds;
    }
    EXPECT_NEAR(offset_variance / (ss::profile_psd(kc, 0.0) * dzeta), 1.0, 0.25);
    EXPECT_THROW(ss::synthesize_profile(kc, 3, dx, 1), surfscatter::Error);
    EXPECT_THROW(ss::synthesize_profile(kc, 64, 0.0, 1), surfscatter::Error);
}
