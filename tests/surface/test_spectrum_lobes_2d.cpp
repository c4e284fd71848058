// SpectrumLobes2d against an independent computation written here: the Poisson series e^{-g} sum g^m/m! P-hat^{*m}
// with every self-convolution a direct 2-D linear convolution of the map's periodogram on its lattice (no FFT).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/spectrum_lobes_2d.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::surface;

namespace {

// A function on lattice nodes -h .. h per axis.
struct Lattice {
    long h = 0;
    std::vector<double> v;
    explicit Lattice(long half) : h(half), v(std::size_t((2 * half + 1) * (2 * half + 1)), 0.0) {}
    double& at(long i, long j) { return v[std::size_t((j + h) * (2 * h + 1) + (i + h))]; }
    double get(long i, long j) const {
        return std::abs(i) > h || std::abs(j) > h ? 0.0 : v[std::size_t((j + h) * (2 * h + 1) + (i + h))];
    }
};

// The unit-mass periodogram on the full plane of a square n x n lattice (even n): Hermitian mirror of the half-plane
// storage, the Nyquist bins split half and half between +- n/2.
Lattice unit_periodogram(const Psd2d& p) {
    const long n = long(p.nx), half = n / 2;
    Lattice out(half);
    const double sum = p.integral() / (p.dzeta_x * p.dzeta_y);
    for (long j = -half; j <= half; ++j)
        for (long i = -half; i <= half; ++i) {
            const long kx = std::abs(i), ky = i >= 0 ? j : -j;
            const std::size_t row = std::size_t((ky % n + n) % n);
            double w = 1.0;
            if (std::abs(i) == half) w *= 0.5;
            if (std::abs(j) == half) w *= 0.5;
            out.at(i, j) = w * p.values[row * p.half_nx() + std::size_t(kx)] / sum;  // sum of nodes = 1
        }
    return out;
}

// a * b (sums over nodes; unit-mass node weights), kept on nodes -h .. h.
Lattice convolve(const Lattice& a, const Lattice& b, long h) {
    Lattice out(h);
    for (long j = -h; j <= h; ++j)
        for (long i = -h; i <= h; ++i) {
            double s = 0;
            for (long bj = -b.h; bj <= b.h; ++bj)
                for (long bi = -b.h; bi <= b.h; ++bi) {
                    const double w = b.v[std::size_t((bj + b.h) * (2 * b.h + 1) + (bi + b.h))];
                    if (w != 0) s += w * a.get(i - bi, j - bj);
                }
            out.at(i, j) = s;
        }
    return out;
}

}  // namespace

TEST(SpectrumLobes2d, MatchesDirectPoissonSeriesOfConvolutions) {
    // 32^2 at 0.1 um, Gaussian ACV l = 0.4 um: the spectrum falls by e^-39 at Nyquist, the 2-fold lattice (p = 2,
    // out to 63 rad/um) holds every order that matters up to g = 5 without folding.
    const GaussianAcv truth(0.05, 0.4);
    const heightmap::HeightMap map = synthesize_surface(truth, {32, 32, 0.1}, 5);
    const Psd2d spectrum = estimate_psd(map, Window::rectangular, heightmap::Form::none);
    const SpectrumLobes2d lobes(spectrum, 6.0);
    EXPECT_EQ(lobes.padding(), 2u);
    EXPECT_LT(lobes.edge_fraction(), 1e-4);  // the highest orders reach the outer quarter, folding nothing
    for (std::size_t r = 0; r < lobes.rows(); ++r) EXPECT_NEAR(lobes.row_mass_before_scaling(r), 1.0, 1e-8) << r;

    const Lattice p1 = unit_periodogram(spectrum);
    constexpr long kHalf = 40;  // nodes kept (p * Nyquist is node 32)
    constexpr int kOrders = 36;
    std::vector<Lattice> orders{p1};
    for (int m = 2; m <= kOrders; ++m) orders.push_back(convolve(orders.back(), p1, kHalf));
    const double dz2 = spectrum.dzeta_x * spectrum.dzeta_y;
    double worst = 0;
    for (double g : {0.01, 0.1, 0.3, 1.0, 1.0 * std::pow(10.0, 0.5 / 12), 2.0, 5.0}) {
        double peak = 0, error = 0;
        for (long j = -32; j <= 32; ++j)
            for (long i = -32; i <= 32; ++i) {
                double direct = 0, term = std::exp(-g);
                for (int m = 1; m <= kOrders; ++m) {
                    term *= g / m;
                    direct += term * orders[std::size_t(m - 1)].get(i, j);
                }
                direct /= dz2;  // node weights to a density, um^2
                const Vec2 zeta(double(i) * spectrum.dzeta_x, double(j) * spectrum.dzeta_y);
                peak = std::max(peak, direct);
                error = std::max(error, std::abs(lobes.eval(g, zeta) - direct));
            }
        std::printf("g = %.4g: max |S_g - direct| / peak = %.3g\n", g, error / peak);
        worst = std::max(worst, error / peak);
    }
    EXPECT_LT(worst, 5e-4);
}

TEST(SpectrumLobes2d, SamplerDensityIsNormalisedAndMatchesDraws) {
    const heightmap::HeightMap map = synthesize_surface(GaussianAcv(0.05, 0.4), {32, 32, 0.1}, 9);
    const SpectrumLobes2d lobes(estimate_psd(map, Window::rectangular, heightmap::Form::none), 6.0);
    for (double g : {0.0, 0.05, 1.3, 5.0}) {
        // The density integrates to 1 (midpoint sum on a grid 4x finer than any row's cells).
        const double h = 0.25 * 2 * kPi / 3.2 / 2, extent = 70;
        double mass = 0;
        for (double y = -extent; y <= extent; y += h)
            for (double x = -extent; x <= extent; x += h) mass += lobes.sample_density(g, false, {x, y}) * h * h;
        EXPECT_NEAR(mass, 1.0, 2e-3) << g;
        // Draws land where the density is positive.
        for (int n = 0; n < 1000; ++n) {
            const Vec2 z = lobes.sample(g, false, (n + 0.5) / 1000, {0.37, 0.71});
            EXPECT_GT(lobes.sample_density(g, false, z), 0.0) << g;
        }
    }
}

TEST(SpectrumLobes2d, RefusesBadInput) {
    const heightmap::HeightMap map = synthesize_surface(GaussianAcv(0.05, 0.4), {32, 32, 0.1}, 9);
    const Psd2d spectrum = estimate_psd(map, Window::rectangular, heightmap::Form::none);
    EXPECT_THROW(SpectrumLobes2d(spectrum, 0.0), Error);
    const SpectrumLobes2d lobes(spectrum, 2.0);
    EXPECT_THROW(lobes.eval(3.0, {0, 0}), Error);
}
