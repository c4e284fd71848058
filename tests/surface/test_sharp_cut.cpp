// The exact sharp-cut statistics (sharp_cut.hpp) against direct quadrature of the high-pass side written here: the
// high-pass ACV from its own definition (1 - F_c) rho_HP(r) = 2 pi int_{zeta_c}^inf P-hat J0(zeta r) zeta dzeta,
// summed over the half periods of J0 and accelerated (iterated averages of the alternating partial sums), and 1 -
// rho_HP from int P-hat (1 - J0) zeta dzeta where it is small. Cutoffs N = 20, 50, 100, 150 at 550 nm, r over the
// whole range the lobe tables transform (1e-16 of the narrowest feature up to 1e6 L).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/sharp_cut.hpp"

namespace surfscatter::surface {
namespace {

// First zero of J0 above x (McMahon's expansion, then Newton with J0' = -J1): j_{0,k} for the smallest k with
// j_{0,k} > x.
double next_j0_zero(double x) {
    int k = std::max(1, static_cast<int>(std::ceil(x / kPi + 0.25)));
    for (;; ++k) {
        const double beta = (k - 0.25) * kPi;
        double z = beta + 1.0 / (8.0 * beta) - 31.0 / (384.0 * beta * beta * beta);
        for (int it = 0; it < 4; ++it) z += j0(z) / j1(z);
        if (z > x * (1.0 + 1e-15)) return z;
    }
}

// int_from^inf P-hat(zeta) J0(zeta r) zeta dzeta: up to the first zero of J0 in ln zeta (decades when r is small),
// then an alternating series over the half periods of J0 whose partial sums are averaged repeatedly.
double j0_integral_from(const RadialStatistics& base, double from, double r) {
    auto f = [&](double z) { return base.psd_unit(z) * j0(z * r) * z; };
    const double first = next_j0_zero(from * r) / r;
    double sum = math::integrate_adaptive([&](double y) { const double z = std::exp(y); return z * f(z); },
                                          std::log(from), std::log(first), 1e-13, 1e-19);
    std::vector<double> partial;
    double a = first;
    for (int k = 0; k < 80; ++k) {
        const double b = next_j0_zero(a * r) / r;
        sum += math::integrate_adaptive(f, a, b, 1e-13, 1e-19);
        if (k >= 40) partial.push_back(sum);  // averages of the later partial sums only
        a = b;
    }
    for (std::size_t level = 1; level < partial.size(); ++level)
        for (std::size_t i = 0; i + level < partial.size(); ++i) partial[i] = 0.5 * (partial[i] + partial[i + 1]);
    return partial.front();
}

// 2 pi int_{zeta_c}^inf P-hat (1 - J0(zeta r)) zeta dzeta, for zeta_c r small: in ln zeta up to Z = 100 / r, then the
// rest of the mass, 1 - F(Z), less the J0 part beyond Z.
double high_side_complement(const RadialStatistics& base, double zeta_c, double r) {
    const double z_end = 100.0 / r;
    auto g = [&](double y) {
        const double z = std::exp(y), x = z * r;
        const double one_minus_j0 = x < 1e-2 ? x * x / 4.0 * (1.0 - x * x / 16.0 + x * x * x * x / 576.0) : 1.0 - j0(x);
        return 2.0 * kPi * z * z * base.psd_unit(z) * one_minus_j0;
    };
    const double y0 = std::log(zeta_c), y1 = std::log(1.0 / r), y2 = std::log(z_end);
    return math::integrate_adaptive(g, y0, std::max(y0, y1), 1e-13, 1e-19) +
           math::integrate_adaptive(g, std::max(y0, y1), y2, 1e-13, 1e-19) + (1.0 - base.radial_cdf(z_end)) -
           2.0 * kPi * j0_integral_from(base, z_end, r);
}

struct Surface {
    double sigma, length, gamma;
};

TEST(SharpCut, HighPassAcvMatchesDirectQuadratureOverTheTableRange) {
    for (const Surface s : {Surface{0.15, 4.0, 4.0}, Surface{0.02, 2.0, 3.0}, Surface{1.0, 0.5, 1.5}})
        for (double n : {20.0, 50.0, 100.0, 150.0}) {
            const auto base = std::make_shared<KCorrelation>(s.sigma, s.length, s.gamma);
            const double zeta_c = cutoff_frequency(550.0, n);
            const SharpCutStatistics hp(base, zeta_c, CutPart::high_pass);
            const double fraction = 1.0 - base->radial_cdf(zeta_c);
            EXPECT_NEAR(hp.sigma_h(), s.sigma * std::sqrt(fraction), 1e-15 * s.sigma);
            double worst_rho = 0, worst_complement = 0;
            for (double lr = -12.0; lr <= 6.01; lr += 0.5) {
                const double r = s.length * std::pow(10.0, lr);
                const double rho = hp.acv_normalized(r);
                if (zeta_c * r < 1e-2) {
                    // Relative accuracy of 1 - rho where the lobe's g (1 - rho) needs it.
                    const double expected = high_side_complement(*base, zeta_c, r) / fraction;
                    const double error = std::abs((1.0 - rho) - expected) / expected;
                    worst_complement = std::max(worst_complement, expected > 1e-6 ? error : 0.0);
                    EXPECT_NEAR(1.0 - rho, expected, 1e-9 * expected + 1e-15 / fraction) << s.gamma << " N " << n << " r " << r;
                } else {
                    const double expected = 2.0 * kPi * j0_integral_from(*base, zeta_c, r) / fraction;
                    worst_rho = std::max(worst_rho, std::abs(rho - expected));
                    EXPECT_NEAR(rho, expected, 2e-13 / fraction) << s.gamma << " N " << n << " r " << r;
                }
            }
            std::printf("gamma %.1f N %3.0f: max |rho_HP - direct| %.2e, max rel. error of 1 - rho_HP (where > 1e-6) %.2e\n", s.gamma,
                        n, worst_rho, worst_complement);
        }
}

TEST(SharpCut, LowPassPartsAddUpToTheBase) {
    const auto base = std::make_shared<KCorrelation>(0.15, 4.0, 4.0);
    const double zeta_c = cutoff_frequency(550.0, 100.0);
    const SharpCutStatistics lp(base, zeta_c, CutPart::low_pass), hp(base, zeta_c, CutPart::high_pass);
    const double f = base->radial_cdf(zeta_c);
    EXPECT_NEAR(lp.sigma_h() * lp.sigma_h() + hp.sigma_h() * hp.sigma_h(), 0.15 * 0.15, 1e-16);
    for (double r : {0.0, 1e-6, 0.3, 4.0, 40.0, 400.0, 4e4, 4e6}) {
        EXPECT_NEAR(f * lp.acv_normalized(r) + (1 - f) * hp.acv_normalized(r), base->acv_normalized(r), 1e-15) << r;
        // Low-pass ACV against direct quadrature over the disc, panel by panel (half periods of J0).
        if (r < 1e3) {
            const int panels = 4 + static_cast<int>(zeta_c * r);
            double d = 0;
            for (int p = 0; p < panels; ++p)
                d += math::integrate_adaptive([&](double z) { return 2 * kPi * z * base->psd_unit(z) * j0(z * r); },
                                              zeta_c * p / panels, zeta_c * (p + 1) / panels, 1e-13, 1e-19);
            EXPECT_NEAR(lp.acv_normalized(r), d / f, 1e-14) << r;
        }
    }
    for (double z : {0.5 * zeta_c, 0.999 * zeta_c, 1.001 * zeta_c, 10 * zeta_c}) {
        EXPECT_EQ(lp.psd_unit(z) > 0, z <= zeta_c);
        EXPECT_EQ(hp.psd_unit(z) > 0, z > zeta_c);
        EXPECT_NEAR(f * lp.radial_cdf(z) + (1 - f) * hp.radial_cdf(z), base->radial_cdf(z), 1e-15);
    }
    EXPECT_EQ(hp.psd_jump_radius(), zeta_c);
    EXPECT_EQ(base->psd_jump_radius(), 0.0);
    // A cut that leaves no micro roughness is an error, not a silent zero.
    EXPECT_THROW(SharpCutStatistics(std::make_shared<GaussianAcv>(0.1, 50.0), 2.0, CutPart::high_pass), Error);
}

}  // namespace
}  // namespace surfscatter::surface
