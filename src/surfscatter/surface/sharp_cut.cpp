#include "surfscatter/surface/sharp_cut.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::surface {

namespace {

constexpr int kPanelNodes = 10;          // Gauss-Legendre nodes per panel
constexpr double kEdgeOmega = 1000.0;     // beyond, D(r) from the edge expansion
constexpr int kEdgeTerms = 5;             // c_0 .. c_4
constexpr int kChebyshevNodes = 24;
constexpr double kChebyshevSpan = 0.5;    // u in [0, 1/2]

struct Rule {
    std::vector<double> x, w;  // on [-1, 1]
    Rule() { math::gauss_legendre(kPanelNodes, x, w); }
};
const Rule& rule() {
    static const Rule r;
    return r;
}

// Taylor coefficients c_n (n < kEdgeTerms) at u = 0 of p(u) from a Chebyshev interpolant on [0, span]:
// d^n T_k / dt^n at t = -1 is (-1)^(k+n) prod_{j<n} (k^2 - j^2) / (2 j + 1).
std::array<double, kEdgeTerms> taylor_at_edge(const std::function<double(double)>& p) {
    const int n = kChebyshevNodes;
    std::vector<double> values(n), a(n, 0.0);
    for (int j = 0; j < n; ++j) values[j] = p(0.5 * kChebyshevSpan * (1.0 + std::cos(kPi * (j + 0.5) / n)));
    for (int k = 0; k < n; ++k) {
        for (int j = 0; j < n; ++j) a[k] += values[j] * std::cos(kPi * k * (j + 0.5) / n);
        a[k] *= (k == 0 ? 1.0 : 2.0) / n;
    }
    std::array<double, kEdgeTerms> c{};
    double factorial = 1.0;
    for (int order = 0; order < kEdgeTerms; ++order) {
        if (order > 0) factorial *= order;
        double derivative = 0.0;  // d^order p / dt^order at t = -1
        for (int k = 0; k < n; ++k) {
            double d = ((k + order) % 2 == 0) ? 1.0 : -1.0;
            for (int j = 0; j < order; ++j) d *= (double(k) * k - double(j) * j) / (2.0 * j + 1.0);
            derivative += a[k] * d;
        }
        c[order] = derivative * std::pow(2.0 / kChebyshevSpan, order) / factorial;
    }
    return c;
}

}  // namespace

SharpCutStatistics::SharpCutStatistics(std::shared_ptr<const RadialStatistics> base, double zeta_c, CutPart part)
    : base_(std::move(base)), zeta_c_(zeta_c), part_(part) {
    if (!(zeta_c > 0.0) || !std::isfinite(zeta_c)) fail("cutoff frequency must be finite and > 0 rad/um, got {}", zeta_c);
    const double l = base_->correlation_length();
    // Panels in x = zeta / zeta_c: four per octave from well below the base's knee x ~ 1/(zeta_c L) up to 1.
    const double x_low = std::min(0.25, 1.0 / (64.0 * zeta_c * l));
    const int count = static_cast<int>(std::ceil(4.0 * std::log2(1.0 / x_low)));
    breaks_.push_back(0.0);
    for (int i = 0; i < count; ++i) breaks_.push_back(std::pow(x_low, double(count - i) / count));
    breaks_.push_back(1.0);

    const double cdf_c = base_->radial_cdf(zeta_c);
    fraction_ = part == CutPart::low_pass ? cdf_c : 1.0 - cdf_c;
    if (!(fraction_ >= kMinCutFraction))
        fail("a sharp cut at {:.6g} rad/um leaves {:.3g} of the variance in the {} part: no {} roughness to model",
             zeta_c, fraction_, part == CutPart::low_pass ? "low-pass" : "high-pass",
             part == CutPart::low_pass ? "macro" : "micro");
    sigma_ = base_->sigma_h() * std::sqrt(fraction_);
    length_ = part == CutPart::low_pass ? std::max(l, 1.0 / zeta_c) : std::min(l, 1.0 / zeta_c);

    const auto c = taylor_at_edge([&](double u) { return base_->psd_unit(zeta_c * std::sqrt(1.0 - u)); });
    double factor = 2.0 * kPi * zeta_c * zeta_c;
    for (int n = 0; n < kEdgeTerms; ++n) {
        edge_coefficients_[n] = factor * c[n];
        factor *= 2.0 * (n + 1);
    }
    base_cdf_at_cut_ = disc_integral(0.0);
}

double SharpCutStatistics::disc_integral(double r) const {
    const double omega = zeta_c_ * std::abs(r);
    if (omega > kEdgeOmega) {
        double sum = 0.0, power = omega;
        for (int n = 0; n < kEdgeTerms; ++n) {
            sum += edge_coefficients_[n] * jn(n + 1, omega) / power;
            power *= omega;
        }
        return sum;
    }
    const Rule& g = rule();
    double sum = 0.0;
    for (std::size_t p = 0; p + 1 < breaks_.size(); ++p) {
        const double a = breaks_[p], b = breaks_[p + 1];
        // At most half a period of J0(omega x) per sub-panel.
        const int pieces = std::max(1, static_cast<int>(std::ceil((b - a) * omega / kPi)));
        const double h = (b - a) / pieces;
        for (int s = 0; s < pieces; ++s) {
            const double mid = a + (s + 0.5) * h;
            double panel = 0.0;
            for (int i = 0; i < kPanelNodes; ++i) {
                const double x = mid + 0.5 * h * g.x[i];
                panel += g.w[i] * x * base_->psd_unit(zeta_c_ * x) * j0(omega * x);
            }
            sum += 0.5 * h * panel;
        }
    }
    return 2.0 * kPi * zeta_c_ * zeta_c_ * sum;
}

double SharpCutStatistics::psd_unit(double zeta) const {
    const bool inside = zeta <= zeta_c_;
    if (inside != (part_ == CutPart::low_pass)) return 0.0;
    return base_->psd_unit(zeta) / fraction_;
}

double SharpCutStatistics::radial_cdf(double zeta) const {
    if (!(zeta > 0.0)) return 0.0;
    if (part_ == CutPart::low_pass) return std::min(1.0, base_->radial_cdf(std::min(zeta, zeta_c_)) / fraction_);
    if (zeta <= zeta_c_) return 0.0;
    return std::clamp((base_->radial_cdf(zeta) - (1.0 - fraction_)) / fraction_, 0.0, 1.0);
}

double SharpCutStatistics::acv_normalized(double r) const {
    const double d = disc_integral(r);
    if (part_ == CutPart::low_pass) return d / base_cdf_at_cut_;
    return (base_->acv_normalized(r) - d) / (1.0 - base_cdf_at_cut_);
}

std::string SharpCutStatistics::cache_key() const {
    return fmt::format("sharp-{}({},zc={:.17g})", part_ == CutPart::low_pass ? "lowpass" : "highpass",
                       base_->cache_key(), zeta_c_);
}

}  // namespace surfscatter::surface
