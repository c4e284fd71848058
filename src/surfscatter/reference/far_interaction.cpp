#include "surfscatter/reference/far_interaction.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "surfscatter/core/error.hpp"

namespace surfscatter::reference {

namespace {

using Complex = std::complex<double>;
constexpr Complex kI{0.0, 1.0};
// Terms up to this order enter the tail estimate; a separation whose terms have not settled by then is refused.
constexpr int kEstimateTerms = 160;

// H_0 .. H_count-1 (first kind) at real z > 0 by upward recurrence: stable for Y, and J's error stays at rounding
// times |H_m| (the recurrence's growing solution is Y), which is all the series needs.
void hankel_orders(double z, int count, std::vector<Complex>& out) {
    out.resize(static_cast<std::size_t>(count));
    out[0] = {::j0(z), ::y0(z)};
    if (count > 1) out[1] = {::j1(z), ::y1(z)};
    for (int m = 1; m + 1 < count; ++m) out[m + 1] = (2.0 * m / z) * out[m] - out[m - 1];
}

// y += c * a .* b without libgcc's NaN-recovering complex multiply.
void multiply_add(Complex* y, const Complex* a, const Complex* b, double c, std::size_t n) {
    auto* __restrict yd = reinterpret_cast<double*>(y);
    const auto* __restrict ad = reinterpret_cast<const double*>(a);
    const auto* __restrict bd = reinterpret_cast<const double*>(b);
    for (std::size_t q = 0; q < n; ++q) {
        yd[2 * q] += c * (ad[2 * q] * bd[2 * q] - ad[2 * q + 1] * bd[2 * q + 1]);
        yd[2 * q + 1] += c * (ad[2 * q] * bd[2 * q + 1] + ad[2 * q + 1] * bd[2 * q]);
    }
}

}  // namespace

int FarInteraction::terms_needed(double step, std::size_t nodes, double range, double k, std::size_t near,
                                 double tolerance) {
    std::vector<Complex> h;
    std::vector<double> s_terms(kEstimateTerms), d_terms(kEstimateTerms);
    int needed = 1;
    // The terms shrink with the separation (a falls as 1/dx, and |H_m / H_0| with it): every separation within 32
    // nodes of the band's edge, then steps of 5 %.
    for (std::size_t d = near + 1; d < nodes; d = std::max(d + 1, std::min(near + 33, d + d / 20))) {
        const double dx = step * static_cast<double>(d);
        if (range >= 0.8 * dx) return 0;
        const double a = k * range * range / (2.0 * dx);
        hankel_orders(k * dx, kEstimateTerms + 1, h);
        // Terms until they are below tolerance / 100 and falling by 0.64 or more per order (beyond m = k dx they fall
        // at least as fast as (range / dx)^2 <= 0.64, below it the factorial wins): the rest sums to less than 3
        // times the last.
        double power = 1.0;  // a^m / m!
        int count = 0;
        bool settled = false;
        const double z = k * dx;
        for (int m = 0; m < kEstimateTerms; ++m) {
            s_terms[m] = power * std::abs(h[m]) / std::abs(h[0]);
            d_terms[m] = power * std::abs(h[m + 1]) / std::abs(h[1]);
            power *= a / (m + 1);
            count = m + 1;
            const bool falling = m > 0 && s_terms[m] <= 0.64 * s_terms[m - 1] && d_terms[m] <= 0.64 * d_terms[m - 1];
            if ((m > z || falling) && s_terms[m] < 1e-2 * tolerance && d_terms[m] < 1e-2 * tolerance) {
                settled = true;
                break;
            }
        }
        if (!settled) return 0;
        double s_tail = 0.0, d_tail = 0.0;
        int m = count;
        while (m > 1) {  // the smallest count whose tail (terms m .. count - 1) is within the tolerance
            if (s_tail + s_terms[m - 1] > tolerance || d_tail + d_terms[m - 1] > tolerance) break;
            --m;
            s_tail += s_terms[m];
            d_tail += d_terms[m];
        }
        needed = std::max(needed, m);
        if (needed > kMaxTerms) return 0;
    }
    return needed;
}

FarInteraction::FarInteraction(double step, const std::vector<double>& h, const std::vector<double>& dh, double k,
                               std::size_t near, double tolerance)
    : n_(h.size()), size_(padded_fft_size(h.size())), dh_(dh), plans_(size_) {
    const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
    const double mid = 0.5 * (*lo + *hi), range = *hi - *lo;
    h_.resize(n_);
    for (std::size_t j = 0; j < n_; ++j) h_[j] = h[j] - mid;
    terms_ = terms_needed(step, n_, range, k, near, tolerance);
    if (terms_ == 0)
        fail("exact-1d: the far-field expansion does not converge for a height range of {} um beyond {} nodes", range,
             near);
    const auto count = static_cast<std::size_t>(terms_);
    single_.assign(count, Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(size_)));
    odd_ = single_;
    slope_ = single_;
    std::vector<Complex> hankel;
    for (std::size_t d = near + 1; d < n_; ++d) {
        const double dx = step * static_cast<double>(d);
        hankel_orders(k * dx, terms_ + 1, hankel);
        double power = 1.0;  // (-k / (2 dx))^m / m!
        for (std::size_t m = 0; m < count; ++m) {
            const Complex g = step * 0.25 * kI * power * hankel[m];
            const Complex f = step * (-0.25 * k) * kI * power * hankel[m + 1] / dx;
            const auto plus = static_cast<Eigen::Index>(d), minus = static_cast<Eigen::Index>(size_ - d);
            single_[m][plus] = single_[m][minus] = g;
            odd_[m][plus] = odd_[m][minus] = f;
            slope_[m][plus] = f * dx;  // C(d) = f(|d|) d step: the kernel -f dx at j - i = -d
            slope_[m][minus] = -f * dx;
            power *= -k / (2.0 * dx) / static_cast<double>(m + 1);
        }
    }
    Eigen::VectorXcd spectrum(static_cast<Eigen::Index>(size_));
    for (auto* family : {&single_, &odd_, &slope_})
        for (auto& v : *family) {
            plans_.forward(v, spectrum);
            v = spectrum;
        }
}

FarInteraction::~FarInteraction() = default;

double FarInteraction::bytes(std::size_t nodes, int terms) {
    const double size = static_cast<double>(padded_fft_size(nodes)), n = static_cast<double>(nodes), c = sizeof(Complex);
    // 3 terms kernel spectra, 2 terms density and 2 terms output spectra, padded_ and one spectrum-sized temporary; h_, dh_
    // and apply's result and power arrays.
    return c * size * (7.0 * terms + 2.0) + 2.0 * 8.0 * n + (c + 8.0) * n;
}

Eigen::VectorXcd FarInteraction::single(const Eigen::VectorXcd& v) const { return apply(nullptr, &v); }
Eigen::VectorXcd FarInteraction::double_layer(const Eigen::VectorXcd& v) const { return -apply(&v, nullptr); }
Eigen::VectorXcd FarInteraction::single_minus_double_layer(const Eigen::VectorXcd& single_density,
                                                           const Eigen::VectorXcd& double_density) const {
    return apply(&double_density, &single_density);
}

Eigen::VectorXcd FarInteraction::apply(const Eigen::VectorXcd* double_density, const Eigen::VectorXcd* single_density) const {
    struct Family {
        const std::vector<Eigen::VectorXcd>* kernels;
        const Eigen::VectorXcd* density;
        int offset;   // total power p = 2m + offset
        bool slope;   // the density carries h'_j
        double sign;  // the double layer enters with -1
    };
    std::vector<Family> families;
    if (double_density) {
        families.push_back({&odd_, double_density, 1, false, -1.0});
        families.push_back({&slope_, double_density, 0, true, -1.0});
    }
    if (single_density) families.push_back({&single_, single_density, 0, false, 1.0});
    const int max_power = 2 * (terms_ - 1) + 1;
    const auto size = static_cast<Eigen::Index>(size_);
    if (out_spectra_.empty()) {
        out_spectra_.assign(static_cast<std::size_t>(max_power + 1), Eigen::VectorXcd(size));
        density_.assign(static_cast<std::size_t>(max_power + 1), Eigen::VectorXcd(size));
        padded_ = Eigen::VectorXcd::Zero(size);
    }
    int used = -1;  // out_spectra_[0 .. used] hold sums
    for (const Family& family : families) {
        const int top = 2 * (terms_ - 1) + family.offset;
        padded_.head(static_cast<Eigen::Index>(n_)) = *family.density;
        padded_.tail(size - static_cast<Eigen::Index>(n_)).setZero();
        if (family.slope)
            for (std::size_t j = 0; j < n_; ++j) padded_[static_cast<Eigen::Index>(j)] *= dh_[j];
        for (int b = 0; b <= top; ++b) {  // FFT of h^b w v
            plans_.forward(padded_, density_[b]);
            for (std::size_t j = 0; j < n_; ++j) padded_[static_cast<Eigen::Index>(j)] *= h_[j];
        }
        // The (terms)^2 spectral products block by block of frequencies, so that the spectra they read stay in cache
        // (one pass over memory per array instead of one per product).
        for (std::size_t q0 = 0; q0 < size_; q0 += kBlock) {
            const std::size_t length = std::min(kBlock, size_ - q0);
            for (int a = used + 1; a <= top; ++a) out_spectra_[a].segment(static_cast<Eigen::Index>(q0), static_cast<Eigen::Index>(length)).setZero();
            for (int m = 0; m < terms_; ++m) {
                const int p = 2 * m + family.offset;
                double c = family.sign;  // sign C(p, a) (-1)^a
                for (int a = 0; a <= p; ++a) {
                    multiply_add(out_spectra_[a].data() + q0, (*family.kernels)[m].data() + q0,
                                 density_[p - a].data() + q0, c, length);
                    c *= -static_cast<double>(p - a) / static_cast<double>(a + 1);
                }
            }
        }
        used = std::max(used, top);
    }
    Eigen::VectorXcd out = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(n_));
    std::vector<double> power(n_, 1.0 / static_cast<double>(size_));  // h^a / size (FFTW does not normalise)
    for (int a = 0; a <= used; ++a) {
        plans_.backward(out_spectra_[a], padded_);
        for (std::size_t j = 0; j < n_; ++j) out[static_cast<Eigen::Index>(j)] += power[j] * padded_[static_cast<Eigen::Index>(j)];
        for (std::size_t j = 0; j < n_; ++j) power[j] *= h_[j];
    }
    return out;
}

}  // namespace surfscatter::reference
