// Complex-argument Hankel functions against SciPy's (Amos' algorithm), computed by Debian's /usr/bin/python3.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/hankel.hpp"

namespace sr = surfscatter::reference;
using Complex = std::complex<double>;

namespace {

// Points over the upper half plane: |z| from 1e-3 to 200 (both sides of the series/asymptotic switch at 12),
// arguments from the real axis to the imaginary one (a metal's k n R lies near 85-89 degrees).
std::vector<Complex> sample_points() {
    std::vector<Complex> points;
    for (double r : {1e-3, 0.05, 0.5, 1.0, 2.5, 5.0, 8.0, 11.9, 12.1, 15.0, 25.0, 60.0, 200.0})
        for (double degrees : {0.0, 10.0, 30.0, 45.0, 60.0, 80.0, 85.0, 88.0, 89.5, 90.0, 120.0, 175.0, 180.0})
            points.push_back(std::polar(r, degrees * surfscatter::kDegree));
    return points;
}

// SciPy's H0(z), H1(z) at every point (empty when python3 with scipy is missing).
std::vector<sr::HankelPair> scipy_hankel(const std::vector<Complex>& points) {
    std::string list;
    for (const Complex& z : points) list += fmt::format("complex({:.17g},{:.17g}),", z.real(), z.imag());
    const std::string command = fmt::format(
        "/usr/bin/python3 -c \"import scipy.special as s\nfor z in [{}]:\n print(repr(s.hankel1(0, z).real), "
        "repr(s.hankel1(0, z).imag), repr(s.hankel1(1, z).real), repr(s.hankel1(1, z).imag))\"",
        list);
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    std::vector<sr::HankelPair> out;
    double a, b, c, d;
    while (pipe && out.size() < points.size() && std::fscanf(pipe.get(), "%lf %lf %lf %lf", &a, &b, &c, &d) == 4)
        out.push_back({Complex(a, b), Complex(c, d)});
    if (out.size() < points.size()) out.clear();
    return out;
}

}  // namespace

TEST(Hankel, MatchesScipy) {
    const auto points = sample_points();
    const auto scipy = scipy_hankel(points);
    ASSERT_EQ(scipy.size(), points.size()) << "python3 with scipy is needed";
    double worst_near = 0, worst_far = 0;
    for (std::size_t q = 0; q < points.size(); ++q) {
        const Complex z = points[q], h0 = scipy[q].h0, h1 = scipy[q].h1;
        const auto ours = sr::hankel01(z);
        // Absolute error for |z| <= 12 (relative to max(1, |H|) near the singularity), relative beyond.
        const double e0 = std::abs(ours.h0 - h0) / std::max(1.0, std::abs(h0));
        const double e1 = std::abs(ours.h1 - h1) / std::max(1.0, std::abs(h1));
        if (std::abs(z) <= 12) {
            worst_near = std::max({worst_near, e0, e1});
            EXPECT_LT(e0, 2e-11) << z;
            EXPECT_LT(e1, 2e-11) << z;
        } else {
            const double r0 = std::abs(ours.h0 - h0) / std::abs(h0), r1 = std::abs(ours.h1 - h1) / std::abs(h1);
            worst_far = std::max({worst_far, r0, r1});
            EXPECT_LT(r0, 1e-11) << z;
            EXPECT_LT(r1, 1e-11) << z;
        }
    }
    std::printf("worst absolute error |z| <= 12: %.3g, relative beyond: %.3g\n", worst_near, worst_far);
}

TEST(Hankel, RefusesTheLowerHalfPlaneAndZero) {
    EXPECT_THROW(sr::hankel01(Complex(1.0, -0.1)), surfscatter::Error);
    EXPECT_THROW(sr::hankel01(Complex(0.0, 0.0)), surfscatter::Error);
    EXPECT_THROW(sr::hankel01(Complex(std::nan(""), 1.0)), surfscatter::Error);
}

// The interpolated ray k r against SciPy at 201 radii over [r_lo, r_hi] (hankel01's own bounds: absolute 2e-11 x
// max(1, |H|), relative 1e-11 from |k r| = 13, past the interval that holds hankel01's switch from its series to
// Hankel's expansion at 12) and against hankel01 itself where that is accurate to rounding (|k r| >= 13: within
// 1e-12 of |H|), for the interior wavenumbers of silver at 550 nm and
// aluminium at 450 nm (N = 0.055 + 3.32i and 0.49 + 5.47i, node spacings 55 and 45 nm, 30 decay lengths) and a
// weakly absorbing medium (N = 1.5 + 0.01i, to 40 um).
TEST(Hankel, RayMatchesDirectEvaluation) {
    struct Case {
        Complex index;
        double lambda_um, step_um;
    };
    for (const Case& c : {Case{{0.055, 3.32}, 0.55, 0.055}, Case{{0.49, 5.47}, 0.45, 0.045}, Case{{1.5, 0.01}, 0.55, 0.055}}) {
        const Complex k = c.index * surfscatter::kTwoPi / c.lambda_um;
        const double r_lo = c.step_um, r_hi = std::min(30.0 / k.imag(), 40.0) + 0.5;
        const sr::HankelRay ray(k, r_lo, r_hi);
        double worst_asymptotic = 0;
        for (int q = 0; q <= 20000; ++q) {
            const double r = r_lo + (r_hi - r_lo) * q / 20000.0;
            if (std::abs(k * r) < 13) continue;
            const auto direct = sr::hankel01(k * r), table = ray(r);
            worst_asymptotic = std::max({worst_asymptotic, std::abs(table.h0 - direct.h0) / std::abs(direct.h0),
                                         std::abs(table.h1 - direct.h1) / std::abs(direct.h1)});
        }
        EXPECT_LT(worst_asymptotic, 1e-12) << c.index;
        std::vector<double> radii;
        std::vector<Complex> z;
        for (int q = 0; q <= 200; ++q) {
            radii.push_back(r_lo + (r_hi - r_lo) * q / 200.0);
            z.push_back(k * radii.back());
        }
        const auto scipy = scipy_hankel(z);
        ASSERT_EQ(scipy.size(), z.size()) << "python3 with scipy is needed";
        double worst_near = 0, worst_far = 0;
        for (std::size_t q = 0; q < z.size(); ++q) {
            const Complex zq = z[q], h0 = scipy[q].h0, h1 = scipy[q].h1;
            const auto table = ray(radii[q]);
            worst_near = std::max({worst_near, std::abs(table.h0 - h0) / std::max(1.0, std::abs(h0)),
                                   std::abs(table.h1 - h1) / std::max(1.0, std::abs(h1))});
            if (std::abs(zq) >= 13) {
                worst_far = std::max({worst_far, std::abs(table.h0 - h0) / std::abs(h0),
                                      std::abs(table.h1 - h1) / std::abs(h1)});
            }
        }
        std::printf("N = %g%+gi: against SciPy %.2g (absolute), %.2g (relative, |k r| >= 13); against "
                    "hankel01 beyond |k r| = 13: %.2g\n",
                    c.index.real(), c.index.imag(), worst_near, worst_far, worst_asymptotic);
        EXPECT_LT(worst_near, 2e-11) << c.index;
        EXPECT_LT(worst_far, 1e-11) << c.index;
    }
    EXPECT_THROW(sr::HankelRay(Complex(1.0, 1.0), 0.0, 1.0), surfscatter::Error);
}
