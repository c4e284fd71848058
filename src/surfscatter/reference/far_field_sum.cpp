#include "surfscatter/reference/far_field_sum.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d.hpp"

namespace surfscatter::reference {

std::vector<std::complex<double>> far_field_sum(double k, double x0, double step, const std::vector<double>& h,
                                                const std::vector<std::complex<double>>& a,
                                                const std::vector<std::complex<double>>& b,
                                                const std::vector<std::complex<double>>& c) {
    const std::size_t n = h.size();
    if (n == 0 || a.size() != n || (!b.empty() && b.size() != n) || (!c.empty() && c.size() != n))
        fail("far_field_sum: {} heights with {}, {} and {} coefficients", n, a.size(), b.size(), c.size());
    const std::vector<std::complex<double>> zero(b.empty() || c.empty() ? n : 0);
    const auto& bb = b.empty() ? zero : b;
    const auto& cc = c.empty() ? zero : c;
    std::vector<std::complex<double>> out(kFarFieldSteps + 1);
    // theta and -theta share e^{-i k cos h_j}, and from one direction to the next it changes by e^{-i k dcos h_j}, a
    // small angle e summed by its Taylor series to e^9 (|e| <= 0.05: 3e-20; recomputed exactly every 64 directions,
    // and at every direction when the heights make e larger). e^{-i k sin x_j} follows x_j's uniform step by recurrence
    // (rounding grows to ~n eps, 1e-12 at 10^4 nodes). Heights are taken from their mid-range, whose phase
    // multiplies the sum.
    const auto [h_lo, h_hi] = std::minmax_element(h.begin(), h.end());
    const double h_mid = 0.5 * (*h_lo + *h_hi), h_half = 0.5 * (*h_hi - *h_lo);
    const double max_step = k * h_half * 180.0 / kFarFieldSteps * kDegree;  // |d cos| <= d theta
    const bool recurrence = max_step <= 0.05;  // else exact phases at every direction
    std::vector<double> height(n), phase_re(n), phase_im(n);
    for (std::size_t j = 0; j < n; ++j) height[j] = h[j] - h_mid;
    double previous_co = 0.0;
    for (int q = 0; q <= kFarFieldSteps / 2; ++q) {
        const int mirror = kFarFieldSteps - q;
        const double theta = (-90.0 + 180.0 * q / kFarFieldSteps) * kDegree;
        const double so = std::sin(theta), co = std::cos(theta);
        if (!recurrence || q % 64 == 0) {
            for (std::size_t j = 0; j < n; ++j) {
                const double phase = -k * co * height[j];
                phase_re[j] = std::cos(phase);
                phase_im[j] = std::sin(phase);
            }
        } else {
            const double factor = -k * (co - previous_co);
            for (std::size_t j = 0; j < n; ++j) {
                const double e = factor * height[j], e2 = e * e;
                const double cs = 1.0 - e2 / 2 * (1.0 - e2 / 12 * (1.0 - e2 / 30 * (1.0 - e2 / 56)));
                const double sn = e * (1.0 - e2 / 6 * (1.0 - e2 / 20 * (1.0 - e2 / 42 * (1.0 - e2 / 72))));
                const double re = phase_re[j] * cs - phase_im[j] * sn, im = phase_re[j] * sn + phase_im[j] * cs;
                phase_re[j] = re;
                phase_im[j] = im;
            }
        }
        previous_co = co;
        // sum over j of (A + co B -+ so C) X^(+-1) E, X = e^{-i k sin x_j}, E the height phase: in real arithmetic
        // (libgcc's complex multiply checks every product for NaN).
        const double step_re = std::cos(-k * so * step), step_im = std::sin(-k * so * step);
        double x_re = std::cos(-k * so * x0), x_im = std::sin(-k * so * x0);
        double sum_re = 0.0, sum_im = 0.0, mirror_re = 0.0, mirror_im = 0.0;
        for (std::size_t j = 0; j < n; ++j) {
            const double e_re = phase_re[j], e_im = phase_im[j];
            const double w_re = a[j].real() + co * bb[j].real(), w_im = a[j].imag() + co * bb[j].imag();
            const double c_re = so * cc[j].real(), c_im = so * cc[j].imag();
            const double p_re = w_re * e_re - w_im * e_im, p_im = w_re * e_im + w_im * e_re;  // (A + co B) E
            const double q_re = c_re * e_re - c_im * e_im, q_im = c_re * e_im + c_im * e_re;  // so C E
            const double minus_re = p_re - q_re, minus_im = p_im - q_im, plus_re = p_re + q_re, plus_im = p_im + q_im;
            sum_re += minus_re * x_re - minus_im * x_im;
            sum_im += minus_re * x_im + minus_im * x_re;
            mirror_re += plus_re * x_re + plus_im * x_im;  // times conj(X)
            mirror_im += plus_im * x_re - plus_re * x_im;
            const double next_re = x_re * step_re - x_im * step_im;
            x_im = x_re * step_im + x_im * step_re;
            x_re = next_re;
        }
        const std::complex<double> mid_phase = std::polar(1.0, -k * co * h_mid);
        out[static_cast<std::size_t>(q)] = std::complex<double>(sum_re, sum_im) * mid_phase;
        out[static_cast<std::size_t>(mirror)] = std::complex<double>(mirror_re, mirror_im) * mid_phase;
    }
    return out;
}

}  // namespace surfscatter::reference
