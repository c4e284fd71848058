#include "surfscatter/surface/hankel.hpp"

#include <cmath>
#include <complex>

#include <fftw3.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/fftw_planner.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::surface {
namespace {

// ln Gamma(z) for Re z > 0: Stirling series after shifting |z| above 10 (absolute error ~1e-14).
std::complex<double> log_gamma(std::complex<double> z) {
    std::complex<double> shift = 0.0;
    while (std::abs(z) < 10.0) {
        shift += std::log(z);
        z += 1.0;
    }
    const std::complex<double> zi = 1.0 / z, zi2 = zi * zi;
    const std::complex<double> series =
        zi * (1.0 / 12.0 + zi2 * (-1.0 / 360.0 + zi2 * (1.0 / 1260.0 + zi2 * (-1.0 / 1680.0 + zi2 / 1188.0))));
    return (z - 0.5) * std::log(z) - z + 0.5 * std::log(2.0 * kPi) + series - shift;
}

// Phase of U_0(i eta) = 2^{i eta} Gamma((1 + i eta)/2) / Gamma((1 - i eta)/2) (a unit complex number).
double u0_phase(double eta) { return eta * std::log(2.0) + 2.0 * log_gamma({0.5, 0.5 * eta}).imag(); }

}  // namespace

struct FftLogHankel::Plans {
    fftw_plan forward = nullptr, backward = nullptr;
};

FftLogHankel::FftLogHankel(double r_min, double r_max, int n) : n_(n), plans_(std::make_unique<Plans>()) {
    if (n < 8 || n % 2 != 0) fail("FFTLog size must be even and >= 8, got {}", n);
    if (!(r_min > 0.0) || !(r_max > r_min)) fail("FFTLog range must satisfy 0 < r_min < r_max, got {}..{}", r_min, r_max);
    log_r0_ = std::log(r_min);
    step_ = (std::log(r_max) - log_r0_) / (n - 1);
    // Output grid zeta_0 r_{n-1} ~ 1, moved by < step/2 so that the Nyquist coefficient is real (low ringing).
    const double eta_nyquist = kPi / step_;
    const double target = -(n - 1) * step_;
    const double base = u0_phase(eta_nyquist) / eta_nyquist;
    const double log_kr = base - std::round((base - target) / step_) * step_;
    log_zeta0_ = log_kr - log_r0_;
    const int half = n / 2;
    phase_re_.resize(half + 1);
    phase_im_.resize(half + 1);
    for (int m = 0; m <= half; ++m) {
        const double eta = 2.0 * kPi * m / (n * step_);
        const double phase = m == 0 ? 0.0 : u0_phase(eta) - eta * log_kr;
        phase_re_[m] = std::cos(phase);
        phase_im_[m] = m == half ? 0.0 : std::sin(phase);
    }
    std::vector<double> real(n);
    std::vector<fftw_complex> spectrum(half + 1);
    std::lock_guard lock(heightmap::fftw_planner_mutex());
    plans_->forward = fftw_plan_dft_r2c_1d(n, real.data(), spectrum.data(), FFTW_ESTIMATE | FFTW_UNALIGNED);
    plans_->backward = fftw_plan_dft_c2r_1d(n, spectrum.data(), real.data(), FFTW_ESTIMATE | FFTW_UNALIGNED);
}

FftLogHankel::~FftLogHankel() {
    std::lock_guard lock(heightmap::fftw_planner_mutex());
    fftw_destroy_plan(plans_->forward);
    fftw_destroy_plan(plans_->backward);
}

double FftLogHankel::r(int j) const { return std::exp(log_r0_ + j * step_); }
double FftLogHankel::zeta(int j) const { return std::exp(log_zeta0_ + j * step_); }

std::vector<double> FftLogHankel::transform(const std::vector<double>& f) const {
    if (static_cast<int>(f.size()) != n_) fail("FFTLog input has {} samples, expected {}", f.size(), n_);
    const int half = n_ / 2;
    std::vector<double> a(n_);
    for (int j = 0; j < n_; ++j) a[j] = r(j) * f[j];
    std::vector<fftw_complex> c(half + 1);
    fftw_execute_dft_r2c(plans_->forward, a.data(), c.data());
    // Multiply by u_m and conjugate, so that the backward (e^{+i}) transform evaluates the needed e^{-i} sum.
    for (int m = 0; m <= half; ++m) {
        const double re = c[m][0] * phase_re_[m] - c[m][1] * phase_im_[m];
        const double im = c[m][0] * phase_im_[m] + c[m][1] * phase_re_[m];
        c[m][0] = re;
        c[m][1] = m == half ? 0.0 : -im;
    }
    fftw_execute_dft_c2r(plans_->backward, c.data(), a.data());
    for (int j = 0; j < n_; ++j) a[j] /= n_ * zeta(j);
    return a;
}

double LogGrid::x(int j) const { return std::exp(log_x0 + j * step); }
double LogGrid::position(double x) const { return (std::log(x) - log_x0) / step; }

double cubic_interpolate(const double* y, int n, double t) {
    int i = static_cast<int>(std::floor(t));
    if (i < 1) i = 1;
    if (i > n - 3) i = n - 3;
    const double u = t - i;
    const double y0 = y[i - 1], y1 = y[i], y2 = y[i + 1], y3 = y[i + 2];
    // Lagrange weights for nodes -1, 0, 1, 2.
    return y0 * (-u * (u - 1.0) * (u - 2.0) / 6.0) + y1 * ((u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0) +
           y2 * (-(u + 1.0) * u * (u - 2.0) / 2.0) + y3 * ((u + 1.0) * u * (u - 1.0) / 6.0);
}

}  // namespace surfscatter::surface
