#pragma once
// Hankel functions of the first kind H0(z), H1(z) for complex z with Im z >= 0, z != 0: the Green's function of an
// absorbing medium (libstdc++'s special functions take real arguments only). Ascending series for |z| <= 12
// (absolute error < 2e-11 times max(1, |H|): the terms grow to ~I0(|z|) before they cancel), Hankel's asymptotic expansion beyond
// (up to 20 terms, stopping once they are below 1e-17; relative error < 1e-11; measured 1.1e-11 and 5e-12). tests/reference/test_hankel.cpp checks both against SciPy (Amos' algorithm).
#include <complex>
#include <vector>

namespace surfscatter::reference {

struct HankelPair {
    std::complex<double> h0, h1;
};

// Throws Error for z = 0 or Im z < 0.
HankelPair hankel01(std::complex<double> z);

// hankel01(k r) for one complex k at real r in [r_lo, r_hi] (r_lo > 0), interpolated: Chebyshev series of degree
// 15 in r on intervals of width min(r_lo, 1 / |k|) / 2, fitted to hankel01 at their Chebyshev points (on every
// interval the nearest singularity, r = 0, lies at least 5 half-widths from the centre: the series converge like
// 9.9^-m). As accurate as hankel01 (against SciPy: absolute 2e-11 max(1, |H|); relative 1e-11 from |k r| = 13, past
// the interval holding hankel01's switch at 12) and within 1e-12 of |H| of it where it is Hankel's expansion
// (tests/reference/test_hankel.cpp); several times faster: the metal's interior product integration evaluates it at
// ~250 points per node.
class HankelRay {
public:
    HankelRay(std::complex<double> k, double r_lo, double r_hi);
    // hankel01(k r); r outside [r_lo, r_hi] is evaluated directly.
    HankelPair operator()(double r) const;

private:
    static constexpr int kDegree = 16;  // coefficients per interval and function
    std::complex<double> k_;
    double r_lo_ = 0, r_hi_ = 0, width_ = 0;
    std::vector<std::complex<double>> coefficients_;  // per interval: kDegree for H0, then kDegree for H1
};

}  // namespace surfscatter::reference
