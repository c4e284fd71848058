// Self-convolution and GHS lobe tables: gamma = 2 exactness, unit mass, the Poisson identity (THEORY.md 1.2),
// Monte-Carlo sums of Student-t draws, sampling by CDF inversion, cache round trip and corruption.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "surfscatter/core/paths.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/radial_table.hpp"
#include "surfscatter/surface/scatter_lobe_table.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"

namespace surfscatter::surface {
namespace {

std::vector<double> log_points(double lo, double hi, int n) {
    std::vector<double> x(n);
    for (int i = 0; i < n; ++i) x[i] = lo * std::pow(hi / lo, i / (n - 1.0));
    return x;
}

TEST(SelfConvolution, Gamma2IsKcWithLOverM) {
    const double l = 0.7;
    const KCorrelation kc(1.0, l, 2.0);
    const auto table = SelfConvolutionTable::get(kc, 200);
    double worst = 0.0;
    for (int m : {1, 2, 3, 7, 20, 64, 200}) {
        const KCorrelation expected(1.0, l / m, 2.0);
        for (double zl : log_points(1e-3, 2000.0, 300)) {
            const double z = zl / l;
            worst = std::max(worst, std::abs(table->eval(m, z) / expected.psd_unit(z) - 1.0));
            EXPECT_NEAR(table->radial_cdf(m, z), expected.radial_cdf(z), 2e-6) << "m " << m << " zeta L " << zl;
        }
    }
    EXPECT_LT(worst, 1e-6);
    std::printf("gamma=2 self-convolution max relative error %.3g\n", worst);
}

TEST(SelfConvolution, UnitMassEveryOrder) {
    for (double gamma : {1.5, 3.0, 4.0}) {
        const KCorrelation kc(1.0, 1.0, gamma);
        const auto table = SelfConvolutionTable::get(kc, 400);
        for (int m = 1; m <= 400; m += 13) {
            EXPECT_NEAR(table->radial_cdf(m, 1e30), 1.0, 1e-6) << "gamma " << gamma << " m " << m;
            // Far tail: P-hat^{*m} ~ m P-hat, so the mass outside zeta is ~ m (1 - F(zeta)).
            const double outside = m * (1.0 - kc.radial_cdf(1e6));
            if (std::pow(m, 1.0 / std::min(gamma - 1.0, 2.0)) > 1e3) continue;  // not yet in the tail regime
            EXPECT_NEAR(1.0 - table->radial_cdf(m, 1e6), outside, 1e-6 + 0.02 * outside) << "gamma " << gamma << " m " << m;
        }
    }
}

TEST(SelfConvolution, MonteCarloSumOfStudentDraws) {
    // P-hat is a bivariate Student-t (THEORY.md 2.1); the sum of m i.i.d. draws has density P-hat^{*m}.
    const double gamma = 3.0, l = 1.0;
    const KCorrelation kc(1.0, l, gamma);
    const auto table = SelfConvolutionTable::get(kc, 8);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int m : {2, 5, 8}) {
        const int samples = 200000;
        const std::vector<double> edges = log_points(0.05, 20.0, 16);
        std::vector<int> counts(edges.size() - 1, 0);
        for (int s = 0; s < samples; ++s) {
            double x = 0.0, y = 0.0;
            for (int i = 0; i < m; ++i) {
                const double r = kc.inverse_radial_cdf(uniform(rng)), phi = 2.0 * M_PI * uniform(rng);
                x += r * std::cos(phi);
                y += r * std::sin(phi);
            }
            const double r = std::hypot(x, y);
            const auto it = std::upper_bound(edges.begin(), edges.end(), r);
            if (it != edges.begin() && it != edges.end()) ++counts[it - edges.begin() - 1];
        }
        double chi2 = 0.0;
        for (std::size_t b = 0; b + 1 < edges.size(); ++b) {
            const double expected = samples * (table->radial_cdf(m, edges[b + 1]) - table->radial_cdf(m, edges[b]));
            chi2 += (counts[b] - expected) * (counts[b] - expected) / expected;
        }
        EXPECT_LT(chi2, 45.0) << "m " << m;  // 15 bins: P(chi2_15 > 45) ~ 7e-5
    }
}

TEST(SelfConvolution, InverseCdfRoundTrip) {
    const KCorrelation kc(1.0, 2.0, 2.5);
    const auto table = SelfConvolutionTable::get(kc, 30);
    for (int m : {1, 4, 30})
        for (double u : {1e-9, 1e-3, 0.1, 0.5, 0.9, 0.999, 0.999999})
            EXPECT_NEAR(table->radial_cdf(m, table->inverse_radial_cdf(m, u)), u, 1e-9 + 1e-7 * u);
}

// e^{-g} sum_m g^m/m! P-hat^{*m}
double poisson_series(const SelfConvolutionTable& t, double g, double zeta) {
    double sum = 0.0, weight = std::exp(-g);
    for (int m = 1; m <= t.max_order(); ++m) {
        weight *= g / m;
        sum += weight * t.eval(m, zeta);
    }
    return sum;
}

TEST(ScatterLobe, PoissonIdentityAtNodesAndBetween) {
    for (double gamma : {3.0, 2.5}) {
        const double l = 1.3;
        const KCorrelation kc(1.0, l, gamma);
        const auto lobe = ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));
        const auto conv = SelfConvolutionTable::get(kc, 160);
        double worst = 0.0;
        for (double g : {1e-5, 1e-3, 0.01, 0.137, 1.0, 3.3, 10.0, 42.0}) {
            for (double zl : log_points(1e-3, 2000.0, 200)) {
                const double z = zl / l;
                const double series = poisson_series(*conv, g, z);
                const double err = std::abs(lobe->eval(g, z) / series - 1.0);
                worst = std::max(worst, err);
                EXPECT_LT(err, 1e-6) << "gamma " << gamma << " g " << g << " zeta L " << zl;
            }
        }
        std::printf("gamma=%g lobe vs Poisson series: max relative error %.3g\n", gamma, worst);
    }
}

TEST(ScatterLobe, UnitMassAndSamplingInverse) {
    const std::shared_ptr<const RadialStatistics> gauss = std::make_shared<GaussianAcv>(2.27, 20.9);
    const std::shared_ptr<const RadialStatistics> kc = std::make_shared<KCorrelation>(1.0, 0.5, 1.5);
    for (const auto& s : {gauss, kc}) {
        const auto lobe = ScatterLobeTable::get(s);
        for (double g : {0.0, 1e-6, 0.5, 30.0, 1e3, 1e5, 1e6}) {
            EXPECT_NEAR(lobe->radial_cdf(g, 1e300), 1.0, 1e-5) << s->cache_key() << " g " << g;
            for (double u : {1e-6, 0.3, 0.9, 0.99999}) {
                const double z = lobe->inverse_radial_cdf(g, u);
                ASSERT_TRUE(std::isfinite(z)) << s->cache_key() << " g " << g << " u " << u;
                // Inverted to 1e-13 in ln zeta: the CDF, whose slope in ln zeta is below ~10, to 1e-12.
                EXPECT_NEAR(lobe->radial_cdf(g, z), u, 1e-12) << "g " << g << " u " << u;
            }
            for (double z : {0.0, 1e-9, 1.0, 1e3, 1e9, 1e200}) {
                const double v = lobe->eval(g, z);
                EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << "g " << g << " zeta " << z;
            }
        }
    }
}

// High-pass parts of a sharp cut (first order added exactly, orders m >= 2 tabulated): at every g node and between
// nodes the radial CDF reaches 1 (the broken rows reached 1.0099), the lobe is positive and finite inside the
// hole zeta < zeta_c and beyond, equals its first-order term plus a positive remainder, and the inverse CDF inverts.
TEST(ScatterLobe, HighPassRowsEndAtUnitMass) {
    double worst_mass = 0;
    for (const auto& [sigma, length, gamma] : {std::tuple{0.15, 4.0, 4.0}, std::tuple{0.02, 2.0, 3.0}})
        for (double n : {20.0, 50.0, 100.0, 150.0}) {
            const double zeta_c = cutoff_frequency(550.0, n);
            const auto hp = split_psd(std::make_shared<KCorrelation>(sigma, length, gamma), zeta_c, LowPassFilter::sharp).micro;
            const auto lobe = ScatterLobeTable::get(hp);
            for (int node = -2; node <= 48 * 10; ++node) {
                const double g = node < 0 ? (node == -2 ? 0.0 : 3e-5) : ScatterLobeTable::kMinG * std::pow(10.0, node / 48.0);
                for (double shift : {1.0, 1.0217}) {
                    const double gg = std::min(g * shift, ScatterLobeTable::kMaxG);
                    const double mass = lobe->radial_cdf(gg, 1e300);
                    worst_mass = std::max(worst_mass, std::abs(mass - 1.0));
                    EXPECT_NEAR(mass, 1.0, 1e-5) << "N " << n << " g " << gg;
                }
            }
            for (double g : {1e-4, 0.01, 1.0, 6.0, 100.0}) {
                for (double z : {1e-3 * zeta_c, 0.5 * zeta_c, 0.999 * zeta_c, 1.001 * zeta_c, 3.0 * zeta_c, 1e3 * zeta_c}) {
                    const double v = lobe->eval(g, z);
                    EXPECT_TRUE(std::isfinite(v) && v > 0.0) << "N " << n << " g " << g << " zeta " << z;
                    EXPECT_GE(v, g * std::exp(-g) * hp->psd_unit(z)) << "N " << n << " g " << g << " zeta " << z;
                }
                for (double u : {1e-6, 0.3, 0.9, 0.99999}) {
                    const double z = lobe->inverse_radial_cdf(g, u);
                    EXPECT_NEAR(lobe->radial_cdf(g, z), u, 1e-8 + 1e-6 * u) << "N " << n << " g " << g << " u " << u;
                }
            }
        }
    std::printf("high-pass lobe rows: max |CDF(inf) - 1| = %.2g\n", worst_mass);
}

// eval_at_logs (the BSDF's path: one set of zeta weights for the 4 x 4 stencil, ln(1 - e^{-g}) interpolated with the
// rows) against eval (exact 1 - e^{-g}) over a dense (g, zeta) sweep between nodes, including the tails.
TEST(ScatterLobe, EvalAtLogsMatchesEval) {
    const KCorrelation kc(1.0, 1.3, 3.0);
    const auto lobe = ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));
    double worst = 0.0;
    for (double g : log_points(1.37e-5, 9.9e5, 700))
        for (double zl : log_points(1e-5, 1e5, 400)) {
            const double z = zl / 1.3, exact = lobe->eval(g, z);
            if (exact < 1e-300) continue;
            worst = std::max(worst, std::abs(lobe->eval_at_logs(std::log(g), std::log(z)) / exact - 1.0));
        }
    EXPECT_LT(worst, 1e-7);
    std::printf("eval_at_logs vs eval: max relative difference %.3g\n", worst);
    EXPECT_EQ(lobe->eval_at_logs(std::log(1e7), std::log(2.0)), lobe->eval(1e6, 2.0));  // beyond kMaxG: at kMaxG
    EXPECT_EQ(lobe->eval_at_logs(std::log(2.0), -std::numeric_limits<double>::infinity()),
              lobe->eval_at_logs(std::log(2.0), -1e300));  // zeta = 0: the flat extension
}

TEST(ScatterLobe, CorruptCacheIsRebuilt) {
    const KCorrelation kc(1.0, 3.0, 2.2);
    const auto first = ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));  // builds and writes the cache file
    const std::string key = "lobe:" + kc.cache_key() + ":g=0.0001..1000000x48";
    const auto path = detail::cache_file(key);
    ASSERT_TRUE(std::filesystem::exists(path));
    detail::RadialFamily family;
    std::vector<double> extra;
    ASSERT_TRUE(detail::load_family(key, family, extra));  // intact file: loads, same numbers
    EXPECT_EQ(family.rows.size(), 1u + 10u * 48u + 1u);
    {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        f.write("garbage!", 8);
    }
    EXPECT_FALSE(detail::load_family(key, family, extra));
    std::filesystem::resize_file(path, 100);
    EXPECT_FALSE(detail::load_family(key, family, extra));
    // A statistics whose cache file is garbage before first use: get() rebuilds it and rewrites a valid file.
    const KCorrelation other(1.0, 3.0, 2.3);
    const std::string other_key = "lobe:" + other.cache_key() + ":g=0.0001..1000000x48";
    { std::ofstream(detail::cache_file(other_key), std::ios::binary) << "not a table"; }
    const double value = ScatterLobeTable::get(std::make_shared<KCorrelation>(other))->eval(2.0, 0.3);
    EXPECT_GT(value, 0.0);
    EXPECT_TRUE(detail::load_family(other_key, family, extra));
}

}  // namespace
}  // namespace surfscatter::surface
