// Marginal2D (math/marginal_2d.hpp), against quadrature of its own bilinear definition written out here: the density
// integrates to 1, invert() is the marginal/conditional CDF of that density, sample() inverts invert(), and the
// parameter interpolation mixes the slices linearly.
#include <gtest/gtest.h>

#include <random>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/marginal_2d.hpp"

using namespace surfscatter;

namespace {

std::vector<double> random_grid(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 3.0);
    std::vector<double> v(n);
    for (double& x : v) x = u(rng) * u(rng);
    return v;
}

// Bilinear interpolation of one slice at (x, y), unnormalised.
double bilinear(const std::vector<double>& d, std::size_t offset, std::size_t nx, std::size_t ny, double x, double y) {
    const double px = x * double(nx - 1), py = y * double(ny - 1);
    const std::size_t i = std::min(std::size_t(px), nx - 2), j = std::min(std::size_t(py), ny - 2);
    const double fx = px - double(i), fy = py - double(j);
    auto at = [&](std::size_t a, std::size_t b) { return d[offset + b * nx + a]; };
    return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

// Midpoint-rule integral of the slice over [0, x1] x [0, y1] (fine grid).
double integral(const std::vector<double>& d, std::size_t offset, std::size_t nx, std::size_t ny, double x1, double y1) {
    const int n = 600;
    double s = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) s += bilinear(d, offset, nx, ny, (a + 0.5) / n * x1, (b + 0.5) / n * y1);
    return s * x1 * y1 / (double(n) * n);
}

}  // namespace

TEST(Marginal2D, InvertIsTheCdfOfTheBilinearDensity) {
    const std::size_t nx = 7, ny = 5;
    const auto data = random_grid(nx * ny, 3);
    const Marginal2D m(data, nx, ny, {}, true);
    const double total = integral(data, 0, nx, ny, 1, 1);
    for (const Vec2 p : {Vec2{0.3, 0.6}, Vec2{0.9, 0.2}, Vec2{0.55, 0.95}}) {
        const auto [u, density] = m.invert(p);
        EXPECT_NEAR(density, bilinear(data, 0, nx, ny, p.x, p.y) / total, 1e-9);
        EXPECT_NEAR(u.y, integral(data, 0, nx, ny, 1, p.y) / total, 1e-5);
        // Conditional CDF in x at height y: int_0^x f(s, y) ds / int_0^1 f(s, y) ds.
        double part = 0, row = 0;
        for (int k = 0; k < 20000; ++k) {
            const double s = (k + 0.5) / 20000, f = bilinear(data, 0, nx, ny, s, p.y);
            row += f;
            if (s < p.x) part += f;
        }
        EXPECT_NEAR(u.x, part / row, 1e-4);
        EXPECT_NEAR(m.eval(p), density, 1e-12);
    }
}

TEST(Marginal2D, SampleInvertsInvertAndParametersMixLinearly) {
    const std::size_t nx = 9, ny = 6;
    const auto data = random_grid(3 * 2 * nx * ny, 5);  // parameters of 3 and 2 nodes
    const Marginal2D m(data, nx, ny, {{0.0, 1.0, 3.0}, {-1.0, 1.0}}, true);
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (int k = 0; k < 200; ++k) {
        const double params[2] = {3 * uniform(rng), 2 * uniform(rng) - 1};
        const Vec2 u{uniform(rng), uniform(rng)};
        const auto [p, pdf] = m.sample(u, params);
        const auto [back, pdf_back] = m.invert(p, params);
        EXPECT_NEAR(back.x, u.x, 1e-7);
        EXPECT_NEAR(back.y, u.y, 1e-7);
        EXPECT_NEAR(pdf_back, pdf, 1e-7 * pdf);
    }
    // At parameters (2, 0): halfway between nodes 1 and 3 of the first, halfway between the two of the second; each
    // slice normalised on its own.
    const std::size_t size = nx * ny;
    const Vec2 p{0.37, 0.81};
    double expected = 0;
    for (std::size_t a : {1u, 2u})
        for (std::size_t b : {0u, 1u}) {
            const std::size_t offset = (a * 2 + b) * size;
            expected += 0.25 * bilinear(data, offset, nx, ny, p.x, p.y) / integral(data, offset, nx, ny, 1, 1);
        }
    const double params[2] = {2.0, 0.0};
    EXPECT_NEAR(m.eval(p, params), expected, 1e-6 * expected);
}

TEST(Marginal2D, RefusesBadTables) {
    EXPECT_THROW(Marginal2D({1, 2, 3}, 3, 1, {}, true), Error);
    EXPECT_THROW(Marginal2D({1, 2, 3, -4}, 2, 2, {}, true), Error);
    EXPECT_THROW(Marginal2D({0, 0, 0, 0}, 2, 2, {}, true), Error);
    EXPECT_THROW(Marginal2D({1, 1, 1, 1, 1, 1, 1, 1}, 2, 2, {{1.0, 1.0}}, true), Error);
}
