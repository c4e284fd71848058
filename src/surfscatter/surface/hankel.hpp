#pragma once
// Zeroth-order Hankel transform H0{f}(zeta) = int_0^inf f(r) J0(zeta r) r dr by FFTLog (Talman 1978, Hamilton 2000;
// THEORY.md 2.5) with FFTW3: f sampled on a log grid r_j = r_0 e^{j d}, j < n, gives H0{f} on zeta_j = zeta_0 e^{j d}
// with zeta_0 r_{n-1} ~ 1 and a low-ringing offset. Unbiased (q = 0). Accuracy (tested): with 16+ decades at 256
// points/decade, (1/2pi) H0{rho_KC} matches P-hat to < 1e-6 relative for zeta L in [0.01, 100], gamma 1.5..4, as long
// as outputs are read at least ~2 decades away from the array ends (ringing). Objects are immutable and thread-safe.
#include <memory>
#include <vector>

namespace surfscatter::surface {

class FftLogHankel {
public:
    // Log grid of n points (n even) from r_min to r_max (um).
    FftLogHankel(double r_min, double r_max, int n);
    ~FftLogHankel();
    FftLogHankel(const FftLogHankel&) = delete;
    FftLogHankel& operator=(const FftLogHankel&) = delete;

    int size() const { return n_; }
    double log_step() const { return step_; }
    double r(int j) const;     // input abscissae
    double zeta(int j) const;  // output abscissae
    // H0{f} at zeta(j) from f(r(j)); f.size() == size().
    std::vector<double> transform(const std::vector<double>& f) const;

private:
    int n_;
    double step_, log_r0_, log_zeta0_;
    std::vector<double> phase_re_, phase_im_;  // u_m, m = 0..n/2
    struct Plans;
    std::unique_ptr<Plans> plans_;
};

// Log-spaced grid helper shared by the tables: n points, log spacing, values of ln(x).
struct LogGrid {
    double log_x0 = 0, step = 1;
    int n = 0;
    double x(int j) const;
    double position(double x) const;  // fractional index of x
};

// Four-point (cubic Lagrange) interpolation of y on a uniform grid at fractional position t in [1, n-2]; callers clamp.
double cubic_interpolate(const double* y, int n, double t);

}  // namespace surfscatter::surface
