// The paper's refit series against the exact S_g lobe: relative L1 distance of the scattered lobes (both K
// renormalised, so both carry the same energy) over g and gamma. gamma = 2 is exactly stable (P-hat^{*m} = KC(L/m),
// x = 1), so there the refit with the cumulative-mass truncation must agree with the exact lobe (the 3-sigma rule
// drops orders: ~1 % at small g). The full table of docs/MODELS.md is bench/table_refit_distance.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "disc_albedo.hpp"
#include "lobe_distance.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/ghs.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

TEST(Refit, StableGamma2MatchesTheExactLobe) {
    const double lambda = 1000.0;
    for (double g : {0.1, 10.0}) {
        auto o = test::kc_options(ModelKind::ghs, test::sigma_for_g(g, lambda, 30), 1.0, 2.0);
        const auto exact = make_bsdf(o);
        o.method = GhsMethod::refit;
        o.truncation = Truncation::poisson_mass;
        const auto refit = make_bsdf(o);
        EXPECT_LT(test::lobe_distance(*refit, *exact, lambda), 0.01) << "g " << g;
    }
}

// The 3-sigma rule takes order 2 in where g0 + 3 sqrt(g0) = 2 (g0 = 0.3153). Near specular g ~ g0, where a narrow
// lobe has its mass, so with whole orders entering at once K changed by 3.2 % within +-0.05 deg of that incidence
// and the cubic in cos theta_i through K's nodes put the albedo 0.84 % off (1.0084 at 34.5 deg); the window's
// fractional edge orders (PoissonWindow::within_sigmas) keep K smooth there. sigma 0.03 um, L 10 um, gamma 3,
// 550 nm (k L = 114): the crossing is at theta_i = 35.0 deg.
TEST(Refit, SmoothWhereAnOrderEntersTheThreeSigmaWindow) {
    const double lambda = 550.0, k = 2 * kPi / (lambda * 1e-3);
    auto o = test::kc_options(ModelKind::ghs, 0.03, 10.0, 3.0);
    o.method = GhsMethod::refit;
    const auto bsdf = make_bsdf(o);
    const auto& ghs = dynamic_cast<const GhsBsdf&>(*bsdf);
    double g_edge = 0.3;  // g + 3 sqrt(g) = 2 by Newton
    for (int it = 0; it < 50; ++it) g_edge -= (g_edge + 3 * std::sqrt(g_edge) - 2) / (1 + 1.5 / std::sqrt(g_edge));
    const auto g0 = [&](double theta) {
        const double a = 2 * k * ghs.direct(theta * kDegree, lambda).sigma * std::cos(theta * kDegree);
        return a * a;
    };
    double lo = 0, hi = 80;  // g0 falls with theta_i
    ASSERT_GT(g0(lo), g_edge);
    for (int it = 0; it < 40; ++it) (g0(0.5 * (lo + hi)) > g_edge ? lo : hi) = 0.5 * (lo + hi);
    const double crossing = 0.5 * (lo + hi);
    const auto k_over_cos2 = [&](double theta) {
        return ghs.direct(theta * kDegree, lambda).norm / std::pow(std::cos(theta * kDegree), 2);
    };
    // Measured: 0.26 % across the 0.1 deg (3.2 % with whole orders).
    EXPECT_LT(std::abs(k_over_cos2(crossing + 0.05) / k_over_cos2(crossing - 0.05) - 1), 0.01) << crossing;
    // The tabulated K keeps the albedo within the documented 0.5 % of R = 1 around the crossing (measured 2.9e-4).
    for (double d : {-2.0, -1.0, -0.5, 0.5, 1.0}) {
        const double theta = crossing + d;
        EXPECT_NEAR(test::disc_albedo(*bsdf, spherical_direction(theta * kDegree, 0.4), lambda), 1.0, 5e-3) << theta;
    }
}
