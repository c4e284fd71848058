#pragma once
// Hankel functions of the first kind H0(z), H1(z) for complex z with Im z >= 0, z != 0: the Green's function of an
// absorbing medium (libstdc++'s special functions take real arguments only). Ascending series for |z| <= 12
// (absolute error < 2e-11 times max(1, |H|): the terms grow to ~I0(|z|) before they cancel), Hankel's asymptotic expansion beyond
// (up to 20 terms, stopping once they are below 1e-17; relative error < 1e-11; measured 1.1e-11 and 5e-12). tests/reference/test_hankel.cpp checks both against SciPy (Amos' algorithm).
#include <complex>

namespace surfscatter::reference {

struct HankelPair {
    std::complex<double> h0, h1;
};

// Throws Error for z = 0 or Im z < 0.
HankelPair hankel01(std::complex<double> z);

}  // namespace surfscatter::reference
