// The statistical mode: determinism over threads, the coherent part of a slightly rough perfect conductor against
// the Kirchhoff factor exp(-(2 k sigma cos theta_i)^2), standard errors against the spread of independent runs,
// and interruption.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

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
// factor exp(-(2 k sigma' cos theta_i)^2) of the mirror's, to the Monte Carlo error (~1 %). sigma'^2 is the variance
// the periodic synthesis gives a 36 um profile: the 1-D PSD sigma^2 l/(2 sqrt(pi)) exp(-l^2 zeta^2/4) summed over
// its frequencies 2 pi m / 36 um (m = 0 included: the zero-frequency line; the PSD beyond Nyquist is missing).
TEST(Exact1dStatistics, CoherentPartFollowsKirchhoff) {
    const double sigma = 0.02, theta_i = 30 * kDegree, k = kTwoPi;
    const ss::GaussianAcv surface(sigma, 2.0);
    const auto r = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(30), runs(24, 1, 0));
    double coherent = 0, incoherent = 0, total = 0, uncertainty = 0;
    for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j) {
        coherent += r.coherent[j] * 0.1 * kDegree;
        incoherent += r.incoherent[j] * 0.1 * kDegree;
        total += r.intensity[j] * 0.1 * kDegree;
        uncertainty += (r.coherent_stderr[j] + r.incoherent_stderr[j]) * 0.1 * kDegree;  // as if all correlated
    }
    const auto profile = sr::random_profile(surface, stat_options(30), 36, 1);
    const double dzeta = kTwoPi / (static_cast<double>(profile.h_um.size()) * profile.spacing_um);
    double variance = 0;
    for (int m = 0; m <= static_cast<int>(profile.h_um.size() / 2); ++m)
        variance += (m == 0 ? 1 : 2) * sigma * sigma * 2.0 / (2 * std::sqrt(surfscatter::kPi)) *
                    std::exp(-std::pow(2.0 * m * dzeta, 2) / 4) * dzeta;
    const double expected = std::exp(-4 * k * k * variance * std::pow(std::cos(theta_i), 2));
    std::printf("coherent %.4f expected %.4f (sigma' %.4f) incoherent %.4f total %.6f (uncertainty %.2g)\n", coherent,
                expected, std::sqrt(variance), incoherent, total, uncertainty);
    EXPECT_NEAR(coherent, expected, 0.01);
    EXPECT_NEAR(total, 1.0, 1e-3);  // each realization conserves energy
    // The controlled parts add up to the plain mean within their errors.
    EXPECT_NEAR(coherent + incoherent, total, uncertainty);
}

// Two independent sets of profiles differ by their combined standard error: within 2 of them at ~95 % of the
// directions where the incoherent part is not negligible (the controlled estimates, 24 realizations each: with fewer
// the control is not used).
TEST(Exact1dStatistics, StandardErrorsMatchTheSpread) {
    const ss::KCorrelation surface(0.1, 1.0, 3.0);
    const auto a = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(10), runs(24, 100, 0));
    const auto b = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), stat_options(10), runs(24, 200, 0));
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

// Issue 34 item 4: on a smooth surface (KC sigma 0.005 um, L 1.5 um, gamma 3; k sigma 0.057 at 550 nm) the mean
// incoherent part is first-order perturbation theory within 2 % plus twice its standard error in every 3 deg bin
// from -90 deg (validity's bins) holding at least 1 % of the peak, specular ones included (before the synthesis kept
// its zero-frequency line they were 0.45-0.55 of it), at normal and oblique incidence, s and p. Perturbation theory
// here, for a perfect conductor and a plane wave from theta: per radian over the incident power
//   s: 4 k^3 cos(theta) cos^2(theta_o) P1(k sin theta_o - k sin theta),
//   p: 4 k^3 (1 - sin(theta) sin(theta_o))^2 / cos(theta) P1(k sin theta_o - k sin theta),
// with the cut's PSD in closed form, P1(zeta) = sigma^2 L / (2 (1 + L^2 zeta^2)^(3/2)) for gamma = 3; the beam
// averages it over its plane waves K = k sin(theta), weighted by their power cos(theta) |A(K)|^2 with
// |A|^2 ~ exp(-(K - k sin theta_i)^2 g^2 / 2) (the taper exp(-x^2/g^2)).
TEST(Exact1dStatistics, SmoothSurfaceMatchesPerturbationTheory) {
    const double sigma = 0.005, corr = 1.5, g = 6, lambda = 550, k = kTwoPi / (lambda * 1e-3);
    const ss::KCorrelation surface(sigma, corr, 3.0);
    const auto psd = [&](double zeta) { return sigma * sigma * corr / (2 * std::pow(1 + corr * corr * zeta * zeta, 1.5)); };
    for (const double theta_i_deg : {0.0, 40.0})
        for (const auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
            const auto options = reference_test::solver_options(lambda, theta_i_deg, pol, g);
            sr::StatisticalOptions st;
            st.length_um = 30;
            st.realizations = 24;
            st.seed = 1;
            const auto r = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), options, st);
            const double alpha = k * std::sin(theta_i_deg * kDegree);
            const auto plane = [&](double theta_o, double theta) {
                const double p1 = psd(k * std::sin(theta_o) - k * std::sin(theta));
                return pol == sr::Polarisation::s
                           ? 4 * k * k * k * std::cos(theta) * std::pow(std::cos(theta_o), 2) * p1
                           : 4 * k * k * k * std::pow(1 - std::sin(theta) * std::sin(theta_o), 2) / std::cos(theta) * p1;
            };
            const auto beam = [&](double theta_o) {
                double sum = 0, weight = 0;
                for (int q = -400; q <= 400; ++q) {  // K over +-8/g
                    const double kx = alpha + q * 0.02 / g;
                    if (std::abs(kx) >= k) continue;
                    const double w = std::sqrt(k * k - kx * kx) * std::exp(-std::pow((kx - alpha) * g, 2) / 2);
                    sum += w * plane(theta_o, std::asin(kx / k));
                    weight += w;
                }
                return sum / weight;
            };
            // 3 deg bins from -90 deg: the mean of each curve and of the standard error over the bin.
            const int bins = 60;
            std::vector<double> exact(bins, 0), theory(bins, 0), stderr_(bins, 0), count(bins, 0);
            for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j) {
                const int b = std::min(bins - 1, static_cast<int>(std::floor((r.theta_o_rad[j] / kDegree + 90) / 3)));
                exact[b] += r.incoherent[j];
                stderr_[b] += r.incoherent_stderr[j];
                theory[b] += beam(r.theta_o_rad[j]);
                ++count[b];
            }
            double peak = 0;
            for (int b = 0; b < bins; ++b) peak = std::max(peak, exact[b] / count[b]);
            int used = 0, specular = 0;
            double worst = 0;
            for (int b = 0; b < bins; ++b) {
                if (exact[b] / count[b] < 0.01 * peak) continue;
                ++used;
                const double centre = -90 + 3 * b + 1.5;
                if (std::abs(centre - theta_i_deg) < 3) ++specular;
                const double error = std::abs(exact[b] - theory[b]) / theory[b];
                worst = std::max(worst, error);
                EXPECT_LE(std::abs(exact[b] - theory[b]), 0.02 * theory[b] + 2 * stderr_[b])
                    << "theta_i " << theta_i_deg << ", bin at " << centre << " deg: exact / theory "
                    << exact[b] / theory[b] << ", relative standard error " << stderr_[b] / exact[b];
            }
            std::printf("[ measured ] theta_i %g %s: %d bins, worst |exact / theory - 1| %.4f\n", theta_i_deg,
                        pol == sr::Polarisation::s ? "s" : "p", used, worst);
            EXPECT_GE(used, 8);
            EXPECT_GE(specular, 2);  // the bins either side of specular are among them
            EXPECT_NEAR(r.beam_half_width_rad, 2 / (k * g * std::cos(theta_i_deg * kDegree)), 1e-12);
        }
}

// Issue 34 item 2: the control variate does not bias the incoherent part. 10^4 realizations of a cheap case (KC
// sigma 0.08 um, L 1 um, gamma 3, k sigma 0.5, 8 um profiles under a 1.5 um beam at 1000 nm: 81 nodes): the
// controlled and plain estimates agree within their combined standard error at every direction out to 70 deg, and
// the control reduces the variance.
TEST(Exact1dStatistics, ControlVariateIsUnbiased) {
    const ss::KCorrelation surface(0.08, 1.0, 3.0);
    const auto options = reference_test::solver_options(1000, 20, sr::Polarisation::s, 1.5);
    sr::StatisticalOptions st;
    st.length_um = 8;
    st.realizations = 10000;
    st.seed = 7;
    const auto r = sr::solve_exact_1d_statistics(surface, sm::Conductor::perfect(), options, st);
    ASSERT_EQ(r.realizations, 10000u);
    std::vector<double> z, reduction;
    for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j) {
        if (std::abs(r.theta_o_rad[j]) > 70 * kDegree) continue;
        z.push_back((r.incoherent[j] - r.incoherent_plain[j]) / std::hypot(r.incoherent_stderr[j], r.incoherent_plain_stderr[j]));
        reduction.push_back(std::pow(r.incoherent_plain_stderr[j] / r.incoherent_stderr[j], 2));
        EXPECT_LT(std::abs(z.back()), 3) << "at " << r.theta_o_rad[j] / kDegree << " deg";
    }
    double mean_z = 0;
    for (const double v : z) mean_z += v / static_cast<double>(z.size());
    std::sort(reduction.begin(), reduction.end());
    std::printf("[ measured ] mean z %.3f, variance reduction: median %.1f, least %.2f\n", mean_z,
                reduction[reduction.size() / 2], reduction.front());
    EXPECT_LT(std::abs(mean_z), 1);
    EXPECT_GT(reduction[reduction.size() / 2], 2);
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
