// The statistical mode: determinism over threads, the coherent part of a slightly rough perfect conductor against
// the Kirchhoff factor exp(-(2 k sigma cos theta_i)^2), standard errors against the spread of independent runs,
// and interruption.
#include <gtest/gtest.h>

#include <cmath>

#include "reference_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace sr = surfscatter::reference;
namespace sm = surfscatter::material;
namespace ss = surfscatter::surface;
using surfscatter::kDegree;
using surfscatter::kTwoPi;

namespace {

sr::Exact1dOptions stat_options(double theta_deg) {
    return reference_test::solver_options(1000, theta_deg, sr::Polarisation::s, 6);
}

sr::StatisticalOptions runs(std::size_t n, std::uint64_t seed, int threads) {
    sr::StatisticalOptions st;
    st.length_um = 36;
    st.realizations = n;
    st.seed = seed;
    st.threads = threads;
    return st;
}

}  // namespace

TEST(Exact1dStatistics, SameResultOnAnyNumberOfThreads) {
    const ss::GaussianAcv surface(0.05, 1.5);
    const auto one = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), runs(3, 9, 1));
    const auto two = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), runs(3, 9, 2));
    ASSERT_EQ(one.realizations, 3u);
    EXPECT_EQ(one.intensity, two.intensity);
    EXPECT_EQ(one.coherent, two.coherent);
    EXPECT_EQ(one.incoherent_stderr, two.incoherent_stderr);
    // The profiles are cuts through the surface: rms height near sigma.
    const auto profile = sr::random_profile(surface, stat_options(20), 36, 9);
    double sum = 0;
    for (double h : profile.h_um) sum += h * h;
    EXPECT_NEAR(std::sqrt(sum / static_cast<double>(profile.h_um.size())), 0.05, 0.02);
    EXPECT_NEAR(profile.x0_um, -18.0, 0.1);
}

// sigma = 0.02 lambda with a correlation length of 2 lambda (rms slope 0.014): the coherent power is the Kirchhoff
// factor exp(-(2 k sigma' cos theta_i)^2) of the mirror's, to the Monte Carlo error of 12 profiles (~1 %). sigma'^2
// is the variance the periodic synthesis gives a 36 um profile: the 1-D PSD sigma^2 l/(2 sqrt(pi)) exp(-l^2 zeta^2/4)
// summed over its frequencies 2 pi m / 36 um, m != 0 (the first cell's ~10 % of sigma^2 is missing).
TEST(Exact1dStatistics, CoherentPartFollowsKirchhoff) {
    const double sigma = 0.02, theta_i = 30 * kDegree, k = kTwoPi;
    const ss::GaussianAcv surface(sigma, 2.0);
    const auto r = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(30), runs(12, 1, 0));
    double coherent = 0, incoherent = 0, total = 0;
    for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j) {
        coherent += r.coherent[j] * 0.1 * kDegree;
        incoherent += r.incoherent[j] * 0.1 * kDegree;
        total += r.intensity[j] * 0.1 * kDegree;
    }
    const auto profile = sr::random_profile(surface, stat_options(30), 36, 1);
    const double dzeta = kTwoPi / (static_cast<double>(profile.h_um.size()) * profile.spacing_um);
    double variance = 0;
    for (int m = 1; m <= static_cast<int>(profile.h_um.size() / 2); ++m)
        variance += 2 * sigma * sigma * 2.0 / (2 * std::sqrt(surfscatter::kPi)) * std::exp(-std::pow(2.0 * m * dzeta, 2) / 4) * dzeta;
    const double expected = std::exp(-4 * k * k * variance * std::pow(std::cos(theta_i), 2));
    std::printf("coherent %.4f expected %.4f (sigma' %.4f) incoherent %.4f total %.6f\n", coherent, expected, std::sqrt(variance), incoherent, total);
    EXPECT_NEAR(coherent, expected, 0.015);
    EXPECT_NEAR(total, 1.0, 1e-3);  // each realization conserves energy
    EXPECT_NEAR(coherent + incoherent, total, 1e-9);
}

// Two independent sets of profiles differ by their combined standard error: within 2 of them at ~95 % of the
// directions where the incoherent part is not negligible.
TEST(Exact1dStatistics, StandardErrorsMatchTheSpread) {
    const ss::KCorrelation surface(0.1, 1.0, 3.0);
    const auto a = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(10), runs(6, 100, 0));
    const auto b = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(10), runs(6, 200, 0));
    int inside = 0, counted = 0;
    for (std::size_t j = 0; j < a.theta_o_rad.size(); ++j) {
        if (std::abs(a.theta_o_rad[j]) > 80 * kDegree) continue;
        const double se = std::hypot(a.incoherent_stderr[j], b.incoherent_stderr[j]);
        ++counted;
        if (std::abs(a.incoherent[j] - b.incoherent[j]) < 2 * se) ++inside;
    }
    std::printf("inside %d of %d\n", inside, counted);
    EXPECT_GT(inside, 0.8 * counted);
    EXPECT_LT(inside, counted);  // errors that never miss would be too large
}

TEST(Exact1dStatistics, InterruptionKeepsWhatIsDone) {
    const ss::GaussianAcv surface(0.05, 1.5);
    surfscatter::request_interrupt();
    const auto r = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), runs(4, 1, 1));
    surfscatter::clear_interrupt();
    EXPECT_EQ(r.realizations, 0u);
}

TEST(Exact1dStatistics, RefusesBadOptions) {
    const ss::GaussianAcv surface(0.05, 1.5);
    EXPECT_THROW(sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), runs(1, 1, 1)),
                 surfscatter::Error);
    auto short_profiles = runs(2, 1, 1);
    short_profiles.length_um = 10;  // cannot hold a 6 um beam 2.5 widths either side
    EXPECT_THROW(sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), short_profiles),
                 surfscatter::Error);
    auto threads = runs(2, 1, 1);
    threads.threads = -1;
    EXPECT_THROW(sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(20), threads),
                 surfscatter::Error);
}
