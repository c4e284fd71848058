// The exact 1-D solver's iterative route (docs/REFERENCE.md, "Solve"): its FFT far part against a direct sum of the
// kernels over the node pairs, and whole solves against the dense LU.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <random>
#include <string>

#include "reference_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/material/refractive_index.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/circulant.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/reference/far_interaction.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace sr = surfscatter::reference;
namespace sm = surfscatter::material;
using surfscatter::kTwoPi;
using Complex = std::complex<double>;
using namespace reference_test;

namespace {

// max_j |a_j - b_j| / max_j |b_j|
double worst_relative(const Eigen::VectorXcd& a, const Eigen::VectorXcd& b) {
    return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// The worst point of |a|^2 - |b|^2 against b's peak intensity.
double worst_intensity(const sr::FarField& a, const sr::FarField& b) {
    const auto ia = a.intensity_per_rad(), ib = b.intensity_per_rad();
    double worst = 0, peak = 0;
    for (std::size_t j = 0; j < ia.size(); ++j) {
        worst = std::max(worst, std::abs(ia[j] - ib[j]));
        peak = std::max(peak, ib[j]);
    }
    return worst / peak;
}

}  // namespace

// The far part's FFT series against the kernels summed pair by pair (glibc's Bessel functions of the true distance
// R), on a rough profile (rms height 0.15 um, height range 0.75 um) at 550 nm: within 1e-9 of the largest entry of
// the result (the series' tail is held to 1e-10 of its first term).
TEST(FarInteraction, MatchesDirectSum) {
    const double step = 0.055, k = kTwoPi / 0.55;
    const std::size_t n = 700, near = 30;
    const auto rough = random_cosines(0.15, 1.0, 6.0, 12, 3);
    std::vector<double> h(n), dh(n);
    for (std::size_t j = 0; j < n; ++j) {
        const double x = step * static_cast<double>(j);
        h[j] = rough(x);
        dh[j] = (rough(x + 1e-5) - rough(x - 1e-5)) / 2e-5;
    }
    std::mt19937 engine(4);
    std::normal_distribution<double> normal;
    Eigen::VectorXcd v(n);
    for (std::size_t j = 0; j < n; ++j) v[j] = Complex(normal(engine), normal(engine));
    Eigen::VectorXcd single = Eigen::VectorXcd::Zero(n), dbl = Eigen::VectorXcd::Zero(n);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = 0; j < n; ++j) {
            if ((i > j ? i - j : j - i) <= near) continue;
            const double dx = step * (double(j) - double(i)), dz = h[j] - h[i], r = std::hypot(dx, dz);
            single[i] += step * 0.25 * Complex(-::y0(k * r), ::j0(k * r)) * v[j];
            dbl[i] += step * Complex(0.0, -0.25 * k) * Complex(::j1(k * r), ::y1(k * r)) / r * (dz - dh[j] * dx) * v[j];
        }
    const sr::FarInteraction far(step, h, dh, k, near, 1e-10);
    const double single_error = worst_relative(far.single(v), single), dbl_error = worst_relative(far.double_layer(v), dbl);
    std::printf("far series: %d terms; single layer %.2g, double layer %.2g\n", far.terms(), single_error, dbl_error);
    EXPECT_LT(single_error, 1e-9);
    EXPECT_LT(dbl_error, 1e-9);
    // A metal's product in one pass (shared inverse FFTs): the single layer of one density minus the double layer of
    // another.
    Eigen::VectorXcd w(n);
    for (std::size_t j = 0; j < n; ++j) w[j] = Complex(normal(engine), normal(engine));
    const double both_error = worst_relative(far.single_minus_double_layer(w, v), far.single(w) - dbl);
    std::printf("single minus double layer: %.2g\n", both_error);
    EXPECT_LT(both_error, 1e-9);
    // Too short a near band for the height range: refused, not extrapolated.
    EXPECT_THROW(sr::FarInteraction(step, h, dh, k, 5, 1e-10), surfscatter::Error);
}

// The flat-surface preconditioner's circulant solve: the head of C^-1 [v; 0] against Eigen's LU of the circulant
// matrix itself (c((i - j) mod L)), and its column recovered from the symbol.
TEST(Circulant, SolvesTheCirculantSystem) {
    const Eigen::Index size = 16, n = 11;
    EXPECT_EQ(sr::padded_fft_size(static_cast<std::size_t>(n)), 32u);
    std::mt19937 engine(2);
    std::normal_distribution<double> normal;
    Eigen::VectorXcd column(size), v(n);
    for (auto& c : column) c = Complex(normal(engine), normal(engine));
    column[0] += 8.0;  // well conditioned
    for (auto& x : v) x = Complex(normal(engine), normal(engine));
    Eigen::MatrixXcd dense(size, size);
    for (Eigen::Index i = 0; i < size; ++i)
        for (Eigen::Index j = 0; j < size; ++j) dense(i, j) = column[(i - j + size) % size];
    Eigen::VectorXcd padded = Eigen::VectorXcd::Zero(size);
    padded.head(n) = v;
    const Eigen::VectorXcd expected = dense.partialPivLu().solve(padded).head(n);
    const sr::Circulant circulant(column);
    EXPECT_LT(worst_relative(circulant.solve_head(v), expected), 1e-13);
    EXPECT_LT(worst_relative(circulant.column(), column), 1e-14);
}

// Whole solves: the iterative route equals the dense LU within 1e-6 of the peak intensity at every direction (measured
// 3e-11 to 4e-9: GMRES stops at a relative residual of 1e-8), for the perfect conductor at normal incidence and
// silver at 50 deg, s and p, on a rough cosine profile (rms height 0.15 lambda at 1 um, 601 nodes), on a cut through
// the supplemental rough surface (KC sigma 0.15 um, L 4 um, gamma 4, at 550 nm: k sigma 1.7; 546 nodes) and on a
// flat profile (where the flat-surface preconditioner is all but the inverse; 546 nodes).
TEST(Exact1dIterative, MatchesDenseLu) {
    const auto cosines = sample_profile(random_cosines(0.15, 1.0, 6.0, 12, 7), 30.0, 0.25);
    const surfscatter::surface::KCorrelation kc(0.15, 4.0, 4.0);
    struct Case {
        const sr::Profile* profile;
        double lambda, g;
    };
    const auto kc_profile = sr::random_profile(kc, solver_options(550, 0, sr::Polarisation::s, 6), 30.0, 11);
    const auto flat = sr::flat_profile(solver_options(550, 0, sr::Polarisation::s, 6), 30.0);
    for (const Case& c : {Case{&cosines, 1000, 10}, Case{&kc_profile, 550, 6}, Case{&flat, 550, 6}})
        for (const char* metal : {"perfect", "Ag"})
            for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
                const double theta_i = std::string(metal) == "perfect" ? 0.0 : 50.0;
                auto o = solver_options(c.lambda, theta_i, pol, c.g);
                const auto conductor = sm::Conductor::from_name(metal);
                o.solver = sr::Exact1dSolver::dense;
                const auto dense = sr::solve_exact_1d(*c.profile, conductor, o);
                o.solver = sr::Exact1dSolver::iterative;
                const auto iterative = sr::solve_exact_1d(*c.profile, conductor, o);
                const double d = worst_intensity(iterative, dense);
                std::printf("%g nm %s %g deg %s: %.2g\n", c.lambda, metal, theta_i,
                            pol == sr::Polarisation::s ? "s" : "p", d);
                EXPECT_LT(d, 1e-6) << c.lambda << " nm " << metal << " " << theta_i << " deg";
            }
}

namespace {

// A weakly absorbing medium of constant index: its interior kernels reach 30 decay lengths, ~80 um at 550 nm.
class WeakAbsorber : public sm::RefractiveIndex {
public:
    std::complex<double> at(double) const override { return {1.5, 0.05}; }
    double min_wavelength_nm() const override { return 200; }
    double max_wavelength_nm() const override { return 2000; }
    std::string name() const override { return "weak absorber"; }
};

}  // namespace

// An interior that reaches past the profile's ends (N = 1.5 + 0.05i, the KC cut of MatchesDenseLu, 546 nodes): the
// flat operator's interior rows are cut at the profile's length, and the iterative route still equals the dense LU
// within 1e-6 of the peak.
TEST(Exact1dIterative, WeakAbsorberMatchesDenseLu) {
    const surfscatter::surface::KCorrelation kc(0.15, 4.0, 4.0);
    const auto profile = sr::random_profile(kc, solver_options(550, 0, sr::Polarisation::s, 6), 30.0, 11);
    const sm::Conductor weak(std::make_shared<WeakAbsorber>());
    for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
        auto o = solver_options(550, 50, pol, 6);
        o.solver = sr::Exact1dSolver::dense;
        const auto dense = sr::solve_exact_1d(profile, weak, o);
        o.solver = sr::Exact1dSolver::iterative;
        const double d = worst_intensity(sr::solve_exact_1d(profile, weak, o), dense);
        std::printf("weak absorber %s: %.2g\n", pol == sr::Polarisation::s ? "s" : "p", d);
        EXPECT_LT(d, 1e-6);
    }
}
