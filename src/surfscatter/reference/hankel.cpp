#include "surfscatter/reference/hankel.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::reference {

namespace {

using Complex = std::complex<double>;
constexpr Complex kI{0.0, 1.0};
constexpr double kEulerGamma = 0.57721566490153286061;
constexpr double kSeriesRadius = 12.0;

// A&S 9.1.10-11 (n = 0, 1): J0, J1 and the series parts of Y0, Y1, summed until the terms are below 1e-17 of the sum's
// largest term.
HankelPair series(Complex z) {
    const Complex q = -0.25 * z * z;  // -(z/2)^2
    Complex term0 = 1.0, term1 = 1.0;  // (-z^2/4)^m / (m!)^2 and / (m! (m+1)!)
    Complex j0 = 1.0, j1 = 1.0, y0_sum = 0.0, y1_sum = 0.0;
    double harmonic = 0.0;  // H_m
    double largest = 1.0;  // squared
    y1_sum = (-kEulerGamma + (1.0 - kEulerGamma)) * term1;  // psi(1) + psi(2) at m = 0
    for (int m = 1; m < 200; ++m) {
        const double dm = m;
        term0 *= q / (dm * dm);
        term1 *= q / (dm * (dm + 1.0));
        harmonic += 1.0 / dm;
        j0 += term0;
        j1 += term1;
        y0_sum += harmonic * term0;
        // psi(m+1) + psi(m+2) = 2 (H_m - gamma) + 1/(m+1)
        y1_sum += (2.0 * (harmonic - kEulerGamma) + 1.0 / (dm + 1.0)) * term1;
        largest = std::max(largest, std::norm(term0));  // squared magnitudes: std::abs is a slow hypot
        if (std::norm(term0) < 1e-34 * largest && std::norm(term1) < 1e-34 * largest) break;
    }
    const Complex half = 0.5 * z;
    j1 *= half;
    const Complex log_half = std::log(half);
    // Y0 = (2/pi) [(ln(z/2) + gamma) J0 - sum_{m>=1} H_m (-z^2/4)^m / (m!)^2]
    const Complex y0 = (2.0 / kPi) * ((log_half + kEulerGamma) * j0 - y0_sum);
    // Y1 = -2/(pi z) + (2/pi) ln(z/2) J1 - (1/pi)(z/2) sum_{m>=0} [psi(m+1) + psi(m+2)] (-z^2/4)^m / (m! (m+1)!)
    const Complex y1 = -2.0 / (kPi * z) + (2.0 / kPi) * log_half * j1 - half * y1_sum / kPi;
    return {j0 + kI * y0, j1 + kI * y1};
}

// H_nu(z) ~ sqrt(2/(pi z)) e^{i(z - nu pi/2 - pi/4)} sum_m i^m a_m(nu) / z^m,
// a_m(nu) = prod_{l=1..m} (4 nu^2 - (2l-1)^2) / (m! 8^m).
HankelPair asymptotic(Complex z) {
    const Complex prefactor = std::sqrt(2.0 / (kPi * z)) * std::exp(kI * (z - 0.25 * kPi));
    Complex sum0 = 1.0, sum1 = 1.0, t0 = 1.0, t1 = 1.0;
    const Complex iz = kI / z;
    for (int m = 1; m <= 20; ++m) {
        const double odd = 2.0 * m - 1.0;
        t0 *= iz * (0.0 - odd * odd) / (8.0 * m);
        t1 *= iz * (4.0 - odd * odd) / (8.0 * m);
        sum0 += t0;
        sum1 += t1;
        if (std::norm(t0) < 1e-34 && std::norm(t1) < 1e-34) break;  // the sums are ~1: the rest is below rounding
    }
    return {prefactor * sum0, prefactor * (-kI) * sum1};  // e^{-i pi/2} = -i for nu = 1
}

}  // namespace

HankelPair hankel01(std::complex<double> z) {
    if (!(z.imag() >= 0) || z == Complex(0.0) || !std::isfinite(z.real()) || !std::isfinite(z.imag()))
        fail("Hankel function argument {}{:+}i must be finite, non-zero, with Im z >= 0", z.real(), z.imag());
    return std::norm(z) <= kSeriesRadius * kSeriesRadius ? series(z) : asymptotic(z);
}

}  // namespace surfscatter::reference
