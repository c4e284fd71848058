// Exact conductor Fresnel reflectance: closed forms, an independent real-arithmetic formulation, limits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/math/vec.hpp"

namespace sm = surfscatter::material;
using surfscatter::kDegree;
using C = std::complex<double>;

namespace {

// Born & Wolf / Heavens form in real arithmetic: with a^2 - b^2 = n^2 - k^2 - sin^2, a b = n k,
// Rs = ((a - cos)^2 + b^2) / ((a + cos)^2 + b^2), Rp = Rs ((a - sin tan)^2 + b^2) / ((a + sin tan)^2 + b^2).
sm::FresnelSP heavens(double theta, double n, double k) {
    const double s2 = std::sin(theta) * std::sin(theta), c = std::cos(theta), st = std::sin(theta) * std::tan(theta);
    const double d = n * n - k * k - s2;
    const double root = std::sqrt(d * d + 4 * n * n * k * k);
    const double a = std::sqrt(0.5 * (root + d)), b = std::sqrt(0.5 * (root - d));
    const double rs = ((a - c) * (a - c) + b * b) / ((a + c) * (a + c) + b * b);
    const double rp = rs * ((a - st) * (a - st) + b * b) / ((a + st) * (a + st) + b * b);
    return {rs, rp};
}

// Metals, dielectrics, and an index below 1 (total reflection beyond the critical angle, w purely imaginary).
const C kMetals[] = {{0.2, 3.0}, {1.4, 7.6}, {0.05, 3.9}, {2.5, 3.3}, {1.5, 0.0}, {3.0, 0.1}, {0.8, 0.0}};

}  // namespace

TEST(Fresnel, NormalIncidence) {
    for (const C eta : kMetals) {
        const double expected = std::norm((eta - 1.0) / (eta + 1.0));
        const auto r = sm::fresnel_conductor_sp(1.0, eta);
        EXPECT_NEAR(r.rs, expected, 1e-14);
        EXPECT_NEAR(r.rp, expected, 1e-14);
        EXPECT_NEAR(sm::fresnel_conductor(1.0, eta), expected, 1e-14);
    }
}

TEST(Fresnel, AgreesWithIndependentRealFormulation) {
    double max_error = 0;
    for (const C eta : kMetals)
        for (double deg = 0.5; deg < 90; deg += 0.5) {
            const auto r = sm::fresnel_conductor_sp(std::cos(deg * kDegree), eta);
            const auto h = heavens(deg * kDegree, eta.real(), eta.imag());
            max_error = std::max({max_error, std::abs(r.rs - h.rs), std::abs(r.rp - h.rp)});
        }
    EXPECT_LT(max_error, 1e-12);
}

TEST(Fresnel, GrazingIncidenceReflectsEverything) {
    for (const C eta : kMetals) {
        EXPECT_NEAR(sm::fresnel_conductor(0.0, eta), 1.0, 1e-14);
        EXPECT_GT(sm::fresnel_conductor(std::cos(89.99 * kDegree), eta), 0.99);
    }
    EXPECT_EQ(sm::fresnel_conductor(0.0, C(1.0, 0.0)), 1.0);  // 0/0 limit
    EXPECT_EQ(sm::fresnel_conductor(1.0, C(1.0, 0.0)), 0.0);
}

TEST(Fresnel, PPolarisationHasAPrincipalAngleMinimum) {
    // Rp dips below Rs and has one minimum before grazing (the pseudo-Brewster angle); for a dielectric it is 0 at
    // Brewster's angle atan(n).
    const auto rp_at = [](double deg, C eta) { return sm::fresnel_conductor_sp(std::cos(deg * kDegree), eta).rp; };
    EXPECT_NEAR(rp_at(std::atan(1.5) / kDegree, {1.5, 0.0}), 0.0, 1e-20);
    const C gold{0.2, 3.0};
    double min_deg = 0, min_rp = 2;
    for (double deg = 0; deg < 90; deg += 0.01)
        if (rp_at(deg, gold) < min_rp) { min_rp = rp_at(deg, gold); min_deg = deg; }
    EXPECT_GT(min_deg, 60.0);
    EXPECT_LT(min_deg, 89.0);
    EXPECT_LT(min_rp, sm::fresnel_conductor(1.0, gold));
    // Rs grows monotonically with the angle.
    for (double deg = 1; deg < 90; deg += 1)
        EXPECT_GE(sm::fresnel_conductor_sp(std::cos(deg * kDegree), gold).rs,
                  sm::fresnel_conductor_sp(std::cos((deg - 1) * kDegree), gold).rs);
}

TEST(Fresnel, ExtremeInputs) {
    for (const C eta : {C(0, 0), C(1e-8, 1e-8), C(1e6, 1e6), C(0, 100), C(100, 0)})
        for (double c : {0.0, 1e-12, 0.3, 1.0, 1.0 + 1e-12}) {
            const auto r = sm::fresnel_conductor_sp(c, eta);
            EXPECT_TRUE(r.rs >= 0 && r.rs <= 1 + 1e-12 && r.rp >= 0 && r.rp <= 1 + 1e-12) << eta << " " << c;
        }
    EXPECT_THROW(sm::fresnel_conductor(-0.5, {1, 1}), surfscatter::Error);
    EXPECT_THROW(sm::fresnel_conductor(1.5, {1, 1}), surfscatter::Error);
    EXPECT_THROW(sm::fresnel_conductor(std::nan(""), {1, 1}), surfscatter::Error);
    EXPECT_THROW(sm::fresnel_conductor(0.5, {1, -1}), surfscatter::Error);
    EXPECT_THROW(sm::fresnel_conductor(0.5, {std::numeric_limits<double>::infinity(), 1}), surfscatter::Error);
}

TEST(Conductor, PerfectAndNamed) {
    const auto perfect = sm::Conductor::from_name("perfect");
    EXPECT_TRUE(perfect.is_perfect());
    EXPECT_EQ(perfect.name(), "perfect");
    EXPECT_EQ(perfect.reflectance(0.3, 550), 1.0);
    EXPECT_EQ(perfect.reflectance_sp(0.3, 550).rp, 1.0);
    EXPECT_THROW(perfect.ior(550), surfscatter::Error);

    const auto gold = sm::Conductor::from_name("Au");
    EXPECT_FALSE(gold.is_perfect());
    EXPECT_EQ(gold.name(), "Au");
    const C n = gold.ior(550);
    EXPECT_NEAR(gold.reflectance(1.0, 550), std::norm((n - 1.0) / (n + 1.0)), 1e-14);
    // Rakic LD gold: R(550 nm) = 0.75 at normal incidence (shared data README).
    EXPECT_NEAR(gold.reflectance(1.0, 550), 0.75, 0.01);
    EXPECT_THROW(sm::Conductor::from_name("Xx"), surfscatter::Error);
    EXPECT_THROW(gold.reflectance(1.0, 100), surfscatter::Error);
}
