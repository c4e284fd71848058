// Poisson order sampler: moments, chi-square against the pmf, windows (3-sigma and cumulative mass).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "chi2_harness.hpp"
#include "surfscatter/bsdf/poisson.hpp"

using namespace surfscatter::bsdf;

TEST(Poisson, PmfSumsToOneAndMatchesRecurrence) {
    for (double mean : {0.01, 1.0, 7.5, 700.0, 5000.0}) {
        double sum = 0;
        for (int m = 0; m < int(mean + 20 * std::sqrt(mean) + 40); ++m) sum += poisson_pmf(m, mean);
        EXPECT_NEAR(sum, 1.0, 1e-10) << mean;
    }
    EXPECT_NEAR(poisson_pmf(3, 2.0), std::exp(-2.0) * 8.0 / 6.0, 1e-15);
}

TEST(Poisson, MeanVarianceAndChiSquare) {
    const std::vector<double> means{0.01, 0.5, 3.0, 30.0, 750.0, 1e4};
    const double level = surfscatter::bsdf::test::sidak(0.01, int(means.size()));
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (double mean : means) {
        const int n = mean > 1000 ? 20000 : 200000;
        std::vector<double> counts(int(mean + 12 * std::sqrt(mean) + 20), 0.0);
        double s1 = 0, s2 = 0;
        for (int i = 0; i < n; ++i) {
            const int m = sample_poisson(mean, uniform(rng));
            ASSERT_GE(m, 0);
            ASSERT_LT(m, int(counts.size()));
            counts[m] += 1;
            s1 += m;
            s2 += double(m) * m;
        }
        const double sample_mean = s1 / n, sample_var = s2 / n - sample_mean * sample_mean;
        // 5-sigma bounds on the sample mean and variance.
        EXPECT_NEAR(sample_mean, mean, 5 * std::sqrt(mean / n)) << mean;
        EXPECT_NEAR(sample_var, mean, 5 * mean * std::sqrt((2.0 + 1.0 / mean) / n)) << mean;
        double chi2 = 0, pooled_obs = 0, pooled_exp = 0;
        int cells = 0;
        for (int m = 0; m < int(counts.size()); ++m) {
            const double e = n * poisson_pmf(m, mean);
            if (e < 5) {
                pooled_obs += counts[m];
                pooled_exp += e;
            } else {
                chi2 += (counts[m] - e) * (counts[m] - e) / e;
                ++cells;
            }
        }
        if (pooled_exp > 0) {
            chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
            ++cells;
        }
        if (cells > 1) { EXPECT_GT(surfscatter::bsdf::test::gamma_q(0.5 * (cells - 1), 0.5 * chi2), level) << mean; }
    }
}

TEST(Poisson, WindowsKeepTheRightOrders) {
    // 3-sigma rule: g = 100 keeps 70..130 (both edges integers: whole orders); g = 0.1 keeps m = 1 and m = 2 with
    // 0.05 of its weight (the upper edge 0.1 + 3 sqrt(0.1) = 1.05 lies 0.05 into [1, 2]).
    const auto w = PoissonWindow::within_sigmas(100.0, 3.0, 1);
    EXPECT_EQ(w.first(), 70);
    EXPECT_EQ(w.last(), 130);
    EXPECT_NEAR(w.kept_mass(), 0.9980, 1e-3);
    const auto small = PoissonWindow::within_sigmas(0.1, 3.0, 1);
    EXPECT_EQ(small.first(), 1);
    EXPECT_EQ(small.last(), 2);
    const double hi = 0.1 + 3.0 * std::sqrt(0.1);
    EXPECT_NEAR(small.kept_mass(), poisson_pmf(1, 0.1) + (hi - 1.0) * poisson_pmf(2, 0.1), 1e-15);
    // Below g + 3 sqrt(g) = 1 the minimum order m = 1 alone, whole.
    const auto tiny = PoissonWindow::within_sigmas(0.05, 3.0, 1);
    EXPECT_EQ(tiny.last(), 1);
    EXPECT_DOUBLE_EQ(tiny.kept_mass(), poisson_pmf(1, 0.05));
    // Continuous in the mean: where an edge g -+ 3 sqrt(g) crosses an integer n (an order enters at the top or leaves
    // at the bottom, m = 1 only at the top), the weighted series weight(m) kept_mass changes by O(dg) only.
    for (const int sign : {1, -1})
        for (int n : {1, 2, 3, 7, 40}) {
            const double root = 0.5 * (-3.0 * sign + std::sqrt(9.0 + 4.0 * n)), g = root * root;  // g + sign 3 sqrt(g) = n
            const auto below = PoissonWindow::within_sigmas(g * (1 - 1e-10), 3.0, 1);
            const auto above = PoissonWindow::within_sigmas(g * (1 + 1e-10), 3.0, 1);
            for (int m = 1; m <= int(g + 4 * std::sqrt(g)) + 2; ++m)
                EXPECT_NEAR(below.weight(m) * below.kept_mass(), above.weight(m) * above.kept_mass(), 1e-7)
                    << "g " << g << " order " << m;
        }
    // Mass rule: the kept mass above m = 1 is within epsilon of all of it.
    for (double g : {0.1, 2.0, 50.0, 1000.0}) {
        const auto m = PoissonWindow::by_mass(g, 1e-6, 1);
        EXPECT_GE(m.first(), 1);
        EXPECT_NEAR(m.kept_mass(), 1.0 - std::exp(-g), 1e-6 * (1.0 - std::exp(-g)) + 1e-15) << g;
        double sum = 0;
        for (int k = m.first(); k <= m.last(); ++k) sum += m.weight(k);
        EXPECT_NEAR(sum, 1.0, 1e-12);
    }
}
