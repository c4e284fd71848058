// MapStatistics (`--psd measured`) against references written here (exact_amplitude.hpp): periodic maps synthesised
// with exact spectral amplitudes and random phases, so that each map's own periodogram is known exactly, and the
// self-convolutions of eq. 2 on the map's own lattice, DFT[rho^m] of its circular ACV (no Hankel transform, no table).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"
#include "surfscatter/surface/synthesis.hpp"
#include "exact_amplitude.hpp"

namespace surfscatter::surface {
namespace {

using test::circular_rho;
using test::exact_amplitude_map;
using test::lattice_rings;

double rms(const heightmap::HeightMap& map) {
    double s = 0.0;
    for (double v : map.heights()) s += v * v;
    return std::sqrt(s / static_cast<double>(map.size()));
}

// Poisson weight e^{-g} g^m / m!.
double poisson(double g, int m) { return std::exp(-g + m * std::log(g) - std::lgamma(m + 1.0)); }

// KC with a slow and a fast tail, and a Gaussian ACV whose steep tail log-bin averaging inflated (1.13x at
// zeta l = 6, 2.0x at 9).
std::vector<std::shared_ptr<const RadialStatistics>> test_surfaces() {
    return {std::make_shared<KCorrelation>(0.05, 1.5, 2.0), std::make_shared<KCorrelation>(0.05, 1.5, 4.0),
            std::make_shared<GaussianAcv>(0.05, 1.5)};
}

TEST(MapStatistics, RmsAndRingMeansAreTheMapsOwn) {
    for (const auto& truth : test_surfaces()) {
        const heightmap::HeightMap map = exact_amplitude_map(*truth, 512, 0.1, 3);
        const MapStatistics stats(map, heightmap::Form::none);
        EXPECT_TRUE(stats.periodic());
        EXPECT_NEAR(stats.map_rms(), rms(map), 1e-12 * rms(map)) << truth->cache_key();
        // Parseval over the band: sigma^2 inside Nyquist is the lattice's sum over DC and the rings used (to the
        // quadrature's 1e-9), and the scale that makes it so is within 1 % of 1. The DC bin, where removing the mean
        // left 0, counts with its continuation from the lowest ring (ring 1: the 8 bins around DC).
        const auto rings = lattice_rings(circular_rho(map), 512, 0.1, 1);
        const std::size_t used = stats.rings().zeta.size();
        double band_sum = rings[0].second;
        for (std::size_t r = 0; r < used; ++r)
            band_sum += rings[r].second * stats.rings().count[r];  // P-hat ring mean times its points
        band_sum *= std::pow(2.0 * kPi / (512 * 0.1), 2) * rms(map) * rms(map);
        EXPECT_NEAR(stats.sigma_h() * stats.sigma_h() * stats.radial_cdf(stats.nyquist()) / band_sum, 1.0, 1e-8)
            << truth->cache_key();
        EXPECT_NEAR(stats.band_scale(), 1.0, 0.01) << truth->cache_key();
        EXPECT_NEAR(stats.sigma_h() / rms(map), 1.0, 0.01) << truth->cache_key();
        // Next to nothing is rolled off beyond Nyquist.
        EXPECT_LT(stats.above_band_fraction(), 1e-3) << truth->cache_key();
        // P at each ring's mean radius is the ring's mean periodogram value times that one scale, down the steepest
        // tail.
        for (std::size_t r = 0; r < rings.size(); ++r) {
            if (rings[r].second < 1e-12 * rings[0].second) break;  // the Gaussian's tail below double rounding
            EXPECT_NEAR(stats.psd(rings[r].first) / (stats.band_scale() * rings[r].second * rms(map) * rms(map)), 1.0,
                        1e-6)
                << truth->cache_key() << " ring " << r + 1;
        }
    }
}

// The lobe core e^{-g} sum_m g^m/m! P-hat^{*m} (eq. 1) against the same sum over the lattice self-convolutions of the
// map's own periodogram, ring by ring, wherever it is at least 1 % of its peak; g from 0.01 to 30 (as g = k^2 sigma^2
// (cos + cos)^2 at one wavelength and geometry: the two sides use their own variance in the band for the same k and
// geometry).
TEST(MapStatistics, LobeCoreMatchesTheMapsOwnSelfConvolutions) {
    const std::size_t n = 512;
    const double dx = 0.1;
    for (const auto& truth : test_surfaces()) {
        const heightmap::HeightMap map = exact_amplitude_map(*truth, n, dx, 7);
        const MapStatistics stats(map, heightmap::Form::none);
        const auto rho = circular_rho(map);
        const int orders = 90;
        const auto table = SelfConvolutionTable::get(stats, orders);
        std::vector<std::vector<std::pair<double, double>>> lattice;
        for (int m = 1; m <= orders; ++m) lattice.push_back(lattice_rings(rho, n, dx, m));
        // g scales with the variance inside the visible disc (sigma_rel, THEORY.md 1.1): here the band, without the
        // roll-off beyond Nyquist, for a disc that holds the band.
        const double sigma_ratio2 = std::pow(stats.sigma_h() / rms(map), 2) * stats.radial_cdf(stats.nyquist());
        for (double g_ref : {0.01, 0.3, 3.0, 30.0}) {
            const double g_ours = g_ref * sigma_ratio2;
            std::vector<double> ref(lattice[0].size(), 0.0), ours(lattice[0].size(), 0.0);
            for (std::size_t r = 0; r < ref.size(); ++r) {
                const double zeta = lattice[0][r].first;
                for (int m = 1; m <= orders; ++m) {
                    ref[r] += poisson(g_ref, m) * lattice[m - 1][r].second;
                    ours[r] += poisson(g_ours, m) * (m == 1 ? stats.psd_unit(zeta) : table->eval(m, zeta));
                }
            }
            const double peak = *std::max_element(ref.begin(), ref.end());
            double worst = 0.0;
            std::size_t worst_ring = 0;
            for (std::size_t r = 0; r < ref.size(); ++r) {
                // Beyond a quarter of Nyquist the lattice's circular convolutions fold the widest lobes (gamma 2, g 30) back: no
                // reference there.
                if (ref[r] < 0.01 * peak || r + 1 > n / 8) continue;
                const double e = std::abs(ours[r] / ref[r] - 1.0);
                if (e > worst) {
                    worst = e;
                    worst_ring = r + 1;
                }
            }
            std::printf("%s g %g worst %.4f at ring %zu\n", truth->cache_key().c_str(), g_ref, worst, worst_ring);
            // The exception: the slowest tail (KC gamma 2) at g = 30, whose near-Cauchy lobe sums the most orders
            // through the lattice's DC cell (mean removed: a hole in every discrete convolution that the continuous
            // ramp below the first ring only approximates): 3.7 % at ring 1, 2 % elsewhere.
            const auto* kc = dynamic_cast<const KCorrelation*>(truth.get());
            const double tolerance = kc && kc->gamma() < 3.0 && g_ref > 10.0 ? 0.05 : 0.02;
            EXPECT_LT(worst, tolerance) << truth->cache_key() << " g " << g_ref << " ring " << worst_ring;
        }
    }
}

TEST(MapStatistics, ScalingHeightsScalesSigmaNotTheShape) {
    const KCorrelation kc(0.05, 1.5, 3.0);
    const heightmap::HeightMap map = exact_amplitude_map(kc, 256, 0.1, 9);
    const heightmap::HeightMap scaled = exact_amplitude_map(kc, 256, 0.1, 9, 3.0);
    const MapStatistics a(map, heightmap::Form::plane), b(scaled, heightmap::Form::plane);
    EXPECT_NEAR(b.sigma_h() / a.sigma_h(), 3.0, 1e-9);
    for (double zeta : {0.1, 0.5, 1.0, 3.0, 10.0}) EXPECT_NEAR(b.psd_unit(zeta) / a.psd_unit(zeta), 1.0, 1e-9) << zeta;
}

TEST(MapStatistics, PaddingWithInvalidPointsKeepsTheStatisticsWithinTheirUncertainty) {
    const KCorrelation kc(0.05, 1.0, 3.0);
    const std::size_t n = 256, pad = 32, m = n + 2 * pad;
    const heightmap::HeightMap map = exact_amplitude_map(kc, n, 0.1, 11);
    std::vector<double> heights(m * m, 0.0);
    std::vector<std::uint8_t> valid(m * m, 0);
    for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) {
            heights[(y + pad) * m + x + pad] = map(x, y);
            valid[(y + pad) * m + x + pad] = 1;
        }
    const heightmap::HeightMap padded(m, m, 0.1, 0.1, heights, valid, "padded map");
    const MapStatistics a(map, heightmap::Form::plane), b(padded, heightmap::Form::plane);
    EXPECT_FALSE(b.periodic());
    EXPECT_NEAR(b.map_rms() / a.map_rms(), 1.0, 1e-12);
    // sigma within three of the padded estimate's stated standard errors (the Hann-weighted masked estimate of one
    // realisation against the exact periodogram).
    EXPECT_NEAR(b.sigma_h() / a.sigma_h(), 1.0, 3.0 * b.sigma_relative_error());
    EXPECT_GT(b.sigma_relative_error(), 0.0);
    EXPECT_LT(b.sigma_relative_error(), 0.1);  // measured 0.069: a map 25 L_c wide holds few low rings
    // Ring means agree within three standard errors of the padded (Hann, masked) estimate, from ring 4 to the knee.
    for (double zeta : {1.0, 2.0, 4.0, 8.0}) {
        const double tolerance = 3.0 / std::sqrt(b.ring_samples(zeta));
        EXPECT_NEAR(b.psd(zeta) / a.psd(zeta), 1.0, tolerance) << zeta;
    }
}

}  // namespace
}  // namespace surfscatter::surface

namespace surfscatter::surface {
namespace {

// The stated standard error of sigma against its scatter over 120 independent realisations of non-periodic maps (the
// centre 128^2 of periodic 256^2 KC maps at 0.1 um, L 1 and 0.25 um: Hann window), within three of the scatter's own
// standard errors (measured: 0.091 against 0.103 +- 0.007, 0.030 against 0.027 +- 0.002; with the Hann window's
// bin correlations, as before, 0.127 and 0.041).
TEST(MapStatistics, SigmaStandardErrorMatchesTheScatterOverRealisations) {
  for (double length : {1.0, 0.25}) {
    const KCorrelation kc(0.05, length, 3.0);
    constexpr int kRealisations = 120;
    constexpr std::size_t kSide = 128;
    std::vector<double> sigma, rms_values;
    double stated = 0;
    for (int r = 0; r < kRealisations; ++r) {
        const heightmap::HeightMap big = synthesize_surface(kc, {256, 256, 0.1}, std::uint64_t(100 + r));
        std::vector<double> h(kSide * kSide);
        for (std::size_t y = 0; y < kSide; ++y)
            for (std::size_t x = 0; x < kSide; ++x) h[y * kSide + x] = big(x + 64, y + 64);
        const MapStatistics s(heightmap::HeightMap(kSide, kSide, 0.1, 0.1, h, "crop"), heightmap::Form::plane);
        ASSERT_FALSE(s.periodic());
        sigma.push_back(s.sigma_h());
        rms_values.push_back(s.map_rms());
        stated += s.sigma_relative_error() / kRealisations;
    }
    auto relative_spread = [](const std::vector<double>& v) {
        double mean = 0, m2 = 0;
        for (double x : v) mean += x / double(v.size());
        for (double x : v) m2 += (x - mean) * (x - mean) / double(v.size() - 1);
        return std::sqrt(m2) / mean;
    };
    const double spread = relative_spread(sigma), uncertainty = spread / std::sqrt(2.0 * (kRealisations - 1));
    std::printf("sigma: stated standard error %.4g, scatter over %d realisations %.4g +- %.2g (map rms %.4g)\n",
                stated, kRealisations, spread, uncertainty, relative_spread(rms_values));
    EXPECT_NEAR(stated, spread, 3.0 * uncertainty);
  }
}

}  // namespace
}  // namespace surfscatter::surface
