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

HankelRay::HankelRay(std::complex<double> k, double r_lo, double r_hi) : k_(k), r_lo_(r_lo), r_hi_(r_hi) {
    if (!(r_lo > 0 && r_hi >= r_lo && std::isfinite(r_hi)))
        fail("Hankel table: radii must satisfy 0 < r_lo <= r_hi, got {} and {}", r_lo, r_hi);
    width_ = 0.5 * std::min(r_lo, 1.0 / std::abs(k));
    const auto intervals = static_cast<std::size_t>(std::ceil((r_hi - r_lo) / width_)) + 1;
    coefficients_.assign(intervals * 2 * kDegree, Complex(0.0));
    HankelPair samples[kDegree];
    for (std::size_t q = 0; q < intervals; ++q) {
        const double centre = r_lo + width_ * (static_cast<double>(q) + 0.5);
        for (int j = 0; j < kDegree; ++j)
            samples[j] = hankel01(k * (centre + 0.5 * width_ * std::cos(kPi * (j + 0.5) / kDegree)));
        Complex* c = &coefficients_[q * 2 * kDegree];
        for (int m = 0; m < kDegree; ++m) {  // c_m = (2 / n) sum_j f(x_j) T_m(x_j), halved at m = 0
            Complex a0 = 0.0, a1 = 0.0;
            for (int j = 0; j < kDegree; ++j) {
                const double t = std::cos(kPi * m * (j + 0.5) / kDegree);
                a0 += t * samples[j].h0;
                a1 += t * samples[j].h1;
            }
            const double scale = (m == 0 ? 1.0 : 2.0) / kDegree;
            c[m] = scale * a0;
            c[kDegree + m] = scale * a1;
        }
    }
}

HankelPair HankelRay::operator()(double r) const {
    if (!(r >= r_lo_ && r <= r_hi_)) return hankel01(k_ * r);
    const double position = (r - r_lo_) / width_;
    const auto q = static_cast<std::size_t>(position);
    const double x = 2.0 * (position - static_cast<double>(q)) - 1.0, twice = 2.0 * x;
    const Complex* c = &coefficients_[q * 2 * kDegree];
    // Clenshaw's recurrence for both series, in real arithmetic (libgcc's complex multiply checks for NaN).
    double b0r = 0, b0i = 0, b1r = 0, b1i = 0, d0r = 0, d0i = 0, d1r = 0, d1i = 0;
    for (int m = kDegree - 1; m >= 1; --m) {
        const double n0r = twice * b0r - b1r + c[m].real(), n0i = twice * b0i - b1i + c[m].imag();
        const double e0r = twice * d0r - d1r + c[kDegree + m].real(), e0i = twice * d0i - d1i + c[kDegree + m].imag();
        b1r = b0r, b1i = b0i, b0r = n0r, b0i = n0i;
        d1r = d0r, d1i = d0i, d0r = e0r, d0i = e0i;
    }
    return {Complex(x * b0r - b1r + c[0].real(), x * b0i - b1i + c[0].imag()),
            Complex(x * d0r - d1r + c[kDegree].real(), x * d0i - d1i + c[kDegree].imag())};
}

}  // namespace surfscatter::reference
