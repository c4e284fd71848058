// fast_exp / fast_log / one_minus_exp / fast_atan2 (the BSDF hot path's exp, log and angle) against the standard
// functions.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "surfscatter/math/fast_math.hpp"

namespace surfscatter::math {
namespace {

TEST(FastMath, ExpWithinTwoUlpOfStdExp) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> x(-699.9, 699.9), small(-1.0, 1.0);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i) {
        const double v = i % 2 ? x(rng) : small(rng);
        worst = std::max(worst, std::abs(fast_exp(v) / std::exp(v) - 1.0));
    }
    EXPECT_LT(worst, 4.5e-16);
    std::printf("fast_exp max relative error %.3g\n", worst);
    // Outside the table range: the standard function's values.
    for (double v : {-745.0, -800.0, 710.0, -std::numeric_limits<double>::infinity()})
        EXPECT_EQ(fast_exp(v), std::exp(v)) << v;
    EXPECT_TRUE(std::isnan(fast_exp(std::nan(""))));
}

TEST(FastMath, LogWithinTwoUlpOfStdLog) {
    std::mt19937_64 rng(12);
    std::uniform_real_distribution<double> exponent(-700.0, 700.0), near_one(0.9, 1.1);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i) {
        const double v = i % 2 ? std::exp(exponent(rng)) : near_one(rng);
        // Absolute error for |ln x| < 1 (what a table position needs), relative beyond.
        worst = std::max(worst, std::abs(fast_log(v) - std::log(v)) / std::max(1.0, std::abs(std::log(v))));
    }
    EXPECT_LT(worst, 4.5e-16);
    std::printf("fast_log max error %.3g\n", worst);
    const double denormal = std::numeric_limits<double>::denorm_min();
    for (double v : {0.0, denormal, 1e-310, std::numeric_limits<double>::infinity()})
        EXPECT_EQ(fast_log(v), std::log(v)) << v;
    EXPECT_TRUE(std::isnan(fast_log(-1.0)));
    EXPECT_TRUE(std::isnan(fast_log(std::nan(""))));
}

TEST(FastMath, Atan2WithinOneNanoradianOfStdAtan2) {
    std::mt19937_64 rng(13);
    std::uniform_real_distribution<double> angle(-3.2, 3.2), log_radius(-300.0, 300.0);
    double worst = 0.0;
    for (int i = 0; i < 2000000; ++i) {
        const double phi = angle(rng), r = std::pow(10.0, log_radius(rng));
        const double x = r * std::cos(phi), y = r * std::sin(phi);
        worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
    }
    // The octants' edges and the axes, where the reflections meet.
    for (double x : {1.0, -1.0, 0.5, -2.0})
        for (double y : {0.0, 1e-300, -1e-300, 1.0, -1.0, 0.5, -2.0, x, -x})
            worst = std::max(worst, std::abs(fast_atan2(y, x) - std::atan2(y, x)));
    EXPECT_LT(worst, 1e-9);
    std::printf("fast_atan2 max error %.3g rad\n", worst);
    const double inf = std::numeric_limits<double>::infinity();
    for (double x : {0.0, -0.0, 1.0, -1.0, inf, -inf})
        for (double y : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
            if (x * y != 0.0 && std::isfinite(x * y)) continue;  // a zero or an infinity: std::atan2's exact values
            EXPECT_EQ(fast_atan2(y, x), std::atan2(y, x)) << y << ", " << x;
            EXPECT_EQ(std::signbit(fast_atan2(y, x)), std::signbit(std::atan2(y, x))) << y << ", " << x;
        }
    EXPECT_TRUE(std::isnan(fast_atan2(std::nan(""), 1.0)));
    EXPECT_TRUE(std::isnan(fast_atan2(1.0, std::nan(""))));
}

TEST(FastMath, OneMinusExpKeepsRelativeAccuracy) {
    double worst = 0.0;
    for (double x = 1e-12; x < 1e3; x *= 1.01)
        worst = std::max(worst, std::abs(one_minus_exp(x) / -std::expm1(-x) - 1.0));
    EXPECT_LT(worst, 1.2e-12);
    EXPECT_EQ(one_minus_exp(0.0), 0.0);
    EXPECT_EQ(one_minus_exp(50.0), 1.0);
}

}  // namespace
}  // namespace surfscatter::math
