// The exact 1-D solver against closed forms and independent computations written here: a flat mirror (the
// reflected beam's plane-wave spectrum by direct quadrature), energy conservation of a perfect conductor,
// reciprocity, grating orders (Rayleigh's method), first-order perturbation theory, convergence with sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <map>

#include <Eigen/Dense>

#include "reference_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d.hpp"

namespace sr = surfscatter::reference;
namespace sm = surfscatter::material;
using surfscatter::kDegree;
using surfscatter::kPi;
using surfscatter::kTwoPi;
using Complex = std::complex<double>;
using namespace reference_test;


// The numerical incident power against Thorsos' closed form: they differ at second order in his correction.
TEST(Exact1d, IncidentPowerMatchesThorsos) {
    for (double theta_i : {0.0, 30.0, 60.0, 80.0})
        for (double g : {8.0, 20.0, 100.0}) {
            const double k = kTwoPi, c = std::cos(theta_i * kDegree), t = std::tan(theta_i * kDegree);
            const double correction = (1 + 2 * t * t) / (2 * k * k * g * g * c * c);
            if (correction > 1e-2) continue;
            const double thorsos = sr::thorsos_incident_power(k, theta_i * kDegree, g);
            EXPECT_NEAR(sr::incident_power(k, theta_i * kDegree, g) / thorsos, 1.0, 5 * correction * correction + 1e-9)
                << theta_i << " deg, g " << g;
        }
}

TEST(Exact1d, FlatProfileIsAMirror) {
    const double lambda = 1000, k = kTwoPi / 1.0, g = 8.0;
    const auto flat = sample_profile([](double) { return 0.0; }, 20.0, 0.25);
    for (double theta_i : {0.0, 30.0, 60.0})
        for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
            const auto f = sr::solve_exact_1d(flat, sm::Conductor::perfect(), solver_options(lambda, theta_i, pol, g));
            const auto intensity = f.intensity_per_rad();
            double peak = 0, worst = 0, reference_power = 0;
            for (std::size_t j = 0; j < intensity.size(); j += 5) {
                const double expected = mirror_intensity(k, theta_i * kDegree, g, f.theta_o_rad[j]);
                peak = std::max(peak, expected);
                worst = std::max(worst, std::abs(intensity[j] - expected));
                reference_power += expected * 5 * 0.1 * kDegree;
            }
            std::printf("flat th %g pol %d worst/peak %.3g energy %.9f ref energy %.9f\n", theta_i, int(pol), worst/peak, total_power(f), reference_power);
            EXPECT_LT(worst / peak, 2e-3) << theta_i << " deg";  // diffraction at the profile's ends
            // The test's quadrature of the beam's propagating power gives the same normalisation.
            EXPECT_NEAR(reference_power, 1.0, 1e-5) << theta_i << " deg";
            EXPECT_NEAR(total_power(f), 1.0, 1e-5) << theta_i << " deg";
            EXPECT_GT(intensity[static_cast<std::size_t>(std::lround((90 + theta_i) * 10))], 0.99 * peak);
        }
}

// A rough profile (rms height 0.15 lambda, rms slope ~0.4): a perfect conductor returns all the incident power.
// s to ~2e-4 with the profile's ends 3 beam widths out; p loses ~1e-3 at 6 beam widths (waves scattered along
// the surface leave through its truncated ends) and needs 10.
TEST(Exact1d, PerfectConductorConservesEnergy) {
    const auto rough = random_cosines(0.15, 1.0, 6.0, 12, 7);
    const double g = 8;
    for (double theta_i : {0.0, 30.0, 60.0})
        for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
            const double half = (pol == sr::Polarisation::s ? 3.0 : 10.0) * g;
            const auto f = sr::solve_exact_1d(sample_profile(rough, half, 0.25), sm::Conductor::perfect(),
                                              solver_options(1000, theta_i, pol, g));
            std::printf("energy th %g pol %d : %.3g\n", theta_i, int(pol), total_power(f) - 1);
            EXPECT_NEAR(total_power(f), 1.0, 1e-3) << theta_i << " deg, " << (pol == sr::Polarisation::s ? "s" : "p");
        }
}

// Against 40 points per wavelength: s converges at ~3.5th order (1.2e-3, 1e-4, 2e-5 at 5, 10, 20), p at ~1.5th
// (the spline's piecewise-linear h'' enters p's kernel).
TEST(Exact1d, ConvergesWithSampling) {
    const auto profile = sample_profile(random_cosines(0.15, 1.0, 6.0, 12, 7), 24.0, 0.5);
    for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
        const auto fine = sr::solve_exact_1d(profile, sm::Conductor::perfect(), solver_options(1000, 20, pol, 8, 40));
        double previous = 1;
        for (double ppw : {5.0, 10.0, 20.0}) {
            const double d = pattern_distance(sr::solve_exact_1d(profile, sm::Conductor::perfect(), solver_options(1000, 20, pol, 8, ppw)), fine);
            std::printf("conv pol %d ppw %g %.3g\n", int(pol), ppw, d);
            EXPECT_LT(d, 0.6 * previous) << ppw;
            if (ppw == 10.0) {
                EXPECT_LT(d, pol == sr::Polarisation::s ? 3e-4 : 4e-3);
            }
            previous = d;
        }
    }
}

// Reciprocity: the power scattered from theta_i into theta_s times cos(theta_i) equals that from the reversed
// path. Incidence from theta_s > 0 (from +x) is the mirrored profile's incidence from -x. The bump scatters ~0.04 of
// the power per radian into these directions; s agrees to 2e-4 per radian, p to 3e-3: waves scattered along the
// surface reach the profile's truncated ends in p (in s the surface's zero field stops them) and diffract there,
// about 1e-3 per radian that moves with the profile's length (0.0015, 0.0025, 0.0010 here; 0.0004, 0.0007, 0.0020
// with the ends twice as far).
TEST(Exact1d, Reciprocity) {
    const auto bump = [](double x) { return 0.3 * std::exp(-x * x / 0.3) - 0.2 * std::exp(-(x - 0.6) * (x - 0.6) / 0.2); };
    const auto profile = sample_profile(bump, 60.0, 0.25);
    const auto mirrored = sample_profile([&](double x) { return bump(-x); }, 60.0, 0.25);
    const auto at = [](const sr::FarField& f, double deg) {
        return f.intensity_per_rad()[static_cast<std::size_t>(std::lround((deg + 90) * 10))];
    };
    for (auto pol : {sr::Polarisation::s, sr::Polarisation::p})
        for (auto [ti, ts] : {std::pair{20.0, -40.0}, std::pair{10.0, 50.0}, std::pair{0.0, 70.0}}) {
            const auto forward = sr::solve_exact_1d(profile, sm::Conductor::perfect(), solver_options(1000, ti, pol, 15));
            const auto reverse = sr::solve_exact_1d(ts >= 0 ? mirrored : profile, sm::Conductor::perfect(),
                                                    solver_options(1000, std::abs(ts), pol, 15));
            const double a = at(forward, ts) * std::cos(ti * kDegree), b = at(reverse, ts >= 0 ? ti : -ti) * std::cos(ts * kDegree);
            std::printf("recip pol %d %g->%g %.4g %.4g\n", int(pol), ti, ts, a, b);
            EXPECT_NEAR(a, b, pol == sr::Polarisation::s ? 2e-4 : 3e-3) << ti << " -> " << ts;
        }
}

namespace {

// Rayleigh's method for a perfectly conducting grating h = a cos(K x) under a plane wave (valid for K a < 0.448;
// Petit, Electromagnetic Theory of Gratings, 1980): reflected orders R_m e^{i(alpha_m x + beta_m z)} matched on the
// surface mode by mode with e^{i b a cos Kx} = sum_l i^l J_l(b a) e^{ilKx}. s: psi = 0; p: (beta - alpha h') terms
// vanish, whose mode-n coefficient is i^{n-m} J_{n-m}(beta_m a) (k^2 - alpha_m alpha_n) / beta_m. Returns the
// efficiencies beta_m / beta_0 |R_m|^2 of the propagating orders, keyed by m.
std::map<int, double> rayleigh_efficiencies(double k, double theta_i, double period, double a, sr::Polarisation pol) {
    const int orders = 12, size = 2 * orders + 1;
    const double big_k = kTwoPi / period, alpha0 = k * std::sin(theta_i), beta0 = k * std::cos(theta_i);
    auto alpha = [&](int m) { return alpha0 + m * big_k; };
    auto beta = [&](int m) { return std::sqrt(Complex(k * k - alpha(m) * alpha(m), 0.0)); };
    // J_l(z) for z real or positive imaginary (evanescent beta): J_l(i y) = i^l I_l(y).
    auto bessel_j = [](int l, Complex z) {
        const int n = std::abs(l);
        Complex value = z.imag() == 0 ? Complex(std::cyl_bessel_j(n, z.real()), 0)
                                      : std::pow(Complex(0, 1), n) * std::cyl_bessel_i(n, z.imag());
        return (l < 0 && n % 2 == 1) ? -value : value;
    };
    auto ipow = [](int l) { return std::pow(Complex(0, 1), l); };
    Eigen::MatrixXcd m(size, size);
    Eigen::VectorXcd rhs(size);
    const bool s_pol = pol == sr::Polarisation::s;
    for (int n = -orders; n <= orders; ++n) {
        for (int q = -orders; q <= orders; ++q) {
            const Complex b = beta(q);
            const Complex c = ipow(n - q) * bessel_j(n - q, b * a);
            m(n + orders, q + orders) = s_pol ? c : c * (k * k - alpha(q) * alpha(n)) / b;
        }
        const Complex c0 = std::pow(Complex(0, -1), n) * bessel_j(n, Complex(beta0 * a, 0));
        rhs(n + orders) = s_pol ? -c0 : -c0 * (k * k - alpha0 * alpha(n)) / (-beta0);
    }
    const Eigen::VectorXcd r = m.partialPivLu().solve(rhs);
    std::map<int, double> out;
    for (int q = -orders; q <= orders; ++q)
        if (std::abs(alpha(q)) < k) out[q] = beta(q).real() / beta0 * std::norm(r(q + orders));
    return out;
}

}  // namespace

TEST(Exact1d, GratingOrdersMatchRayleigh) {
    const double lambda = 1000, k = kTwoPi, period = 2.2, a = 0.1, theta_i = 10 * kDegree, g = 15;
    const auto grating = [&](double x) { return a * std::cos(kTwoPi * x / period); };
    for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
        const auto expected = rayleigh_efficiencies(k, theta_i, period, a, pol);
        double expected_sum = 0;
        for (auto [order, e] : expected) expected_sum += e;
        EXPECT_NEAR(expected_sum, 1.0, 1e-9);  // the reference itself conserves energy
        const double half = (pol == sr::Polarisation::s ? 3.0 : 4.0) * g;
        for (double ppw : {10.0, 15.0}) {
            const auto f = sr::solve_exact_1d(sample_profile(grating, half, 0.1), sm::Conductor::perfect(),
                                              solver_options(lambda, theta_i / kDegree, pol, g, ppw));
            // Power around each order: every direction goes to the order nearest in sin(theta_o).
            std::map<int, double> found;
            const auto intensity = f.intensity_per_rad();
            for (std::size_t j = 0; j < intensity.size(); ++j) {
                const double order = (std::sin(f.theta_o_rad[j]) - std::sin(theta_i)) * period / 1.0;
                found[static_cast<int>(std::lround(order))] += intensity[j] * 0.1 * kDegree;
            }
            for (auto [order, e] : expected) {
                // The grating equation: the peak sits at sin(theta_m) = sin(theta_i) + m lambda / period.
                const double theta_m = std::asin(std::sin(theta_i) + order / period);
                std::size_t peak = 0;
                for (std::size_t j = 0; j < intensity.size(); ++j)
                    if (std::abs(f.theta_o_rad[j] - theta_m) < 3 * kDegree && intensity[j] > intensity[peak]) peak = j;
                std::printf("grating pol %d ppw %g order %d: rayleigh %.6f exact %.6f diff %.2g peak at %.1f (theory %.2f)\n", int(pol), ppw, order, e, found[order], found[order]-e, f.theta_o_rad[peak]/kDegree, theta_m/kDegree);
                EXPECT_NEAR(f.theta_o_rad[peak], theta_m, 0.1 * kDegree) << "order " << order;
                EXPECT_NEAR(found[order], e, 2e-4) << "order " << order << ", " << ppw << " points per wavelength";
            }
        }
    }
}

// First-order perturbation theory (Rice 1951) for a perfectly conducting grating h = a cos(K x) of small k a: the
// orders +-1 carry s: e = (k a)^2 cos(theta_i) cos(theta_m),  p: e = (k a)^2 (1 - sin(theta_i) sin(theta_m))^2 /
// (cos(theta_i) cos(theta_m)), from psi(x, h) = 0 or dpsi/dn = 0 expanded about z = 0; the next order is O((k a)^2).
TEST(Exact1d, SmallRoughnessMatchesPerturbationTheory) {
    const double k = kTwoPi, period = 2.2, a = 0.005, theta_i = 25 * kDegree, g = 10;
    for (auto pol : {sr::Polarisation::s, sr::Polarisation::p}) {
        const double half = (pol == sr::Polarisation::s ? 3.0 : 6.0) * g;
        const auto f = sr::solve_exact_1d(sample_profile([&](double x) { return a * std::cos(kTwoPi * x / period); }, half, 0.1),
                                          sm::Conductor::perfect(), solver_options(1000, theta_i / kDegree, pol, g));
        std::map<int, double> found;
        const auto intensity = f.intensity_per_rad();
        for (std::size_t j = 0; j < intensity.size(); ++j)
            found[static_cast<int>(std::lround((std::sin(f.theta_o_rad[j]) - std::sin(theta_i)) * period))] +=
                intensity[j] * 0.1 * kDegree;
        for (int order : {-1, 1}) {
            const double sm_ = std::sin(theta_i) + order / period, cm = std::sqrt(1 - sm_ * sm_);
            const double ka2 = k * a * k * a;
            const double expected = pol == sr::Polarisation::s ? ka2 * std::cos(theta_i) * cm
                                                              : ka2 * std::pow(1 - std::sin(theta_i) * sm_, 2) / (std::cos(theta_i) * cm);
            std::printf("spm pol %d order %d exact %.6g spm %.6g rel %.3g\n", int(pol), order, found[order], expected, found[order] / expected - 1);
            EXPECT_NEAR(found[order] / expected, 1.0, 5e-3) << "order " << order;
        }
    }
}
