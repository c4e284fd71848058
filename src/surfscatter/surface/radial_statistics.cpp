#include "surfscatter/surface/radial_statistics.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"

namespace surfscatter::surface {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEulerGamma = 0.57721566490153286061;

// int_0^{u_c} u e^{-b u} (1 + u)^{-p} du (the KC slope integral in u = L^2 zeta^2), +inf if divergent.
double kc_slope_integral(double p, double b, double u_c) {
    if (b == 0.0 && std::isinf(u_c)) return p > 2.0 ? 1.0 / ((p - 1.0) * (p - 2.0)) : kInf;
    if (b == 0.0 && std::abs(p - 2.0) > 1e-3) {
        // [(1+u)^{2-p}/(2-p) - (1+u)^{1-p}/(1-p)] from 0 to u_c, written with expm1 against cancellation.
        const double l = std::log1p(u_c);
        return std::expm1((2.0 - p) * l) / (2.0 - p) - std::expm1((1.0 - p) * l) / (1.0 - p);
    }
    if (b == 0.0 && p == 2.0) return std::log1p(u_c) - u_c / (1.0 + u_c);
    // Substitution u = e^y - 1 spreads the algebraic tail over a finite y range.
    const double y_max = std::min(std::log1p(u_c), b > 0.0 ? std::log1p(60.0 / b) : 700.0);
    return math::integrate_adaptive(
        [&](double y) {
            const double u = std::expm1(y);
            return u * std::exp(-b * u - p * y) * std::exp(y);
        },
        0.0, y_max, 1e-12);
}

}  // namespace

void require_surface_length(double length_um, const char* what) {
    if (!(length_um >= kMinSurfaceLengthUm && length_um <= kMaxSurfaceLengthUm))
        fail("{} must be between {:g} and {:g} um, got {}", what, kMinSurfaceLengthUm, kMaxSurfaceLengthUm, length_um);
}

void require_kc_gamma(double gamma, const char* what) {
    if (!(gamma >= kMinKcGamma && gamma <= kMaxKcGamma))
        fail("{} must be between {} and {} (KC), got {}", what, kMinKcGamma, kMaxKcGamma, gamma);
}

namespace {

// What the classes accept: positive lengths whose squares and inverse squares are far inside the double range.
void require_representable_length(double length_um, const char* what) {
    if (!(length_um >= 1e-100 && length_um <= 1e100)) fail("{} must be between 1e-100 and 1e100 um, got {}", what, length_um);
}

}  // namespace

double RadialStatistics::psd(double zeta) const { return sigma_h() * sigma_h() * psd_unit(zeta); }
double RadialStatistics::acv(double r) const { return sigma_h() * sigma_h() * acv_normalized(r); }

double RadialStatistics::mean_square_slope(double smoothing_um, double cutoff_zeta) const {
    require_non_negative(smoothing_um, "smoothing scale");
    if (!(cutoff_zeta > 0.0)) fail("cutoff frequency must be > 0 (or +inf for none), got {}", cutoff_zeta);
    // int zeta^2 e^{-s^2 zeta^2} P 2 pi zeta d zeta over y = ln(1 + zeta L).
    const double l = correlation_length(), s2 = smoothing_um * smoothing_um;
    // zeta L up to e^100 (the PSD must not underflow before a divergent tail shows).
    double y_max = std::min(std::log1p(cutoff_zeta * l), 100.0);
    if (s2 > 0.0) y_max = std::min(y_max, std::log1p(40.0 * l / smoothing_um));  // e^{-1600} beyond
    // Evaluated in logs so that huge zeta never overflows: zeta^3 e^{-s^2 zeta^2} P(zeta) (d zeta/dy).
    auto integrand = [&](double y) {
        const double zeta = std::expm1(y) / l;
        const double p = psd(zeta);
        if (!(p > 0.0) || zeta == 0.0) return 0.0;
        return 2.0 * kPi * std::exp(3.0 * std::log(zeta) - s2 * zeta * zeta + std::log(p) + y - std::log(l));
    };
    const double value = math::integrate_adaptive(integrand, 0.0, y_max, 1e-10);
    // A tail that still carries weight at the end of a y range that was not cut off means divergence.
    if (std::isinf(cutoff_zeta) && std::abs(integrand(y_max)) > 1e-12 * std::abs(value)) return kInf;
    return value;
}

double RadialStatistics::total_integrated_scatter(double theta_i_rad, double lambda_nm) const {
    const double s = relevant_roughness(*this, theta_i_rad, lambda_nm);
    const double a = 4.0 * kPi * s * std::cos(theta_i_rad) / (lambda_nm * 1e-3);
    return -std::expm1(-a * a);
}

// ---------------------------------------------------------------------------------------------------------------
KCorrelation::KCorrelation(double sigma_h_um, double corr_length_um, double gamma)
    : sigma_(sigma_h_um), length_(corr_length_um), gamma_(gamma), nu_(0.5 * (gamma - 1.0)) {
    require_representable_length(sigma_h_um, "sigma_h");
    require_representable_length(corr_length_um, "correlation length");
    if (!(gamma > 1.0 && gamma <= kMaxKcGamma)) fail("gamma must be in (1, {}], got {}", kMaxKcGamma, gamma);
    acv_norm_ = std::pow(2.0, 1.0 - nu_) / std::tgamma(nu_);
}

double KCorrelation::psd_unit(double zeta) const {
    const double lz2 = length_ * length_ * zeta * zeta;
    return (gamma_ - 1.0) * length_ * length_ / (2.0 * kPi) * std::exp(-0.5 * (gamma_ + 1.0) * std::log1p(lz2));
}

double KCorrelation::profile_psd_unit(double zeta) const {
    const double log_b = 0.5 * std::log(kPi) + std::lgamma(0.5 * gamma_) - std::lgamma(0.5 * (gamma_ + 1.0));
    return (gamma_ - 1.0) * length_ / (2.0 * kPi) *
           std::exp(log_b - 0.5 * gamma_ * std::log1p(length_ * length_ * zeta * zeta));
}

double KCorrelation::radial_cdf(double zeta) const {
    if (std::isinf(zeta)) return 1.0;
    return -std::expm1(-nu_ * std::log1p(length_ * length_ * zeta * zeta));
}

double KCorrelation::inverse_radial_cdf(double u) const {
    if (u <= 0.0) return 0.0;
    if (u >= 1.0) return kInf;
    return std::sqrt(std::expm1(-std::log1p(-u) / nu_)) / length_;
}

double KCorrelation::acv_normalized(double r) const {
    const double x = std::abs(r) / length_;
    if (gamma_ == 2.0) return std::exp(-x);
    if (gamma_ == 4.0) return (1.0 + x) * std::exp(-x);
    if (gamma_ == 6.0) return (1.0 + x + x * x / 3.0) * std::exp(-x);
    if (x > 700.0) return 0.0;
    if (x == 0.0) return 1.0;
    if (x < 1e-8) {
        // Small-x expansion (THEORY.md 1.5): 1 + x^2/(4(1-nu)) - Gamma(1-nu)/Gamma(1+nu) (x/2)^{2 nu}.
        if (nu_ == std::round(nu_)) {
            // ln 2 - ln x, not ln(2 / x): 2 / x overflows for x below 1e-308 (acv --r 1e-320 printed -nan).
            if (nu_ == 1.0) return 1.0 - 0.5 * x * x * (std::log(2.0) - std::log(x) + 0.5 - kEulerGamma);
            return 1.0 - x * x / (4.0 * (nu_ - 1.0));
        }
        const double power = std::tgamma(1.0 - nu_) / std::tgamma(1.0 + nu_) * std::pow(0.5 * x, 2.0 * nu_);
        return 1.0 + x * x / (4.0 * (1.0 - nu_)) - power;
    }
    return std::min(1.0, acv_norm_ * std::pow(x, nu_) * std::cyl_bessel_k(nu_, x));
}

std::string KCorrelation::cache_key() const {
    return fmt::format("kc(L={:.17g},gamma={:.17g})", length_, gamma_);
}

double KCorrelation::mean_square_slope(double smoothing_um, double cutoff_zeta) const {
    require_non_negative(smoothing_um, "smoothing scale");
    if (!(cutoff_zeta > 0.0)) fail("cutoff frequency must be > 0 (or +inf for none), got {}", cutoff_zeta);
    const double b = smoothing_um * smoothing_um / (length_ * length_);
    const double u_c = std::isinf(cutoff_zeta) ? kInf : length_ * length_ * cutoff_zeta * cutoff_zeta;
    const double integral = kc_slope_integral(0.5 * (gamma_ + 1.0), b, u_c);
    return std::isinf(integral) ? kInf : sigma_ * sigma_ * (gamma_ - 1.0) / (2.0 * length_ * length_) * integral;
}

// ---------------------------------------------------------------------------------------------------------------
GaussianAcv::GaussianAcv(double sigma_h_um, double corr_length_um) : sigma_(sigma_h_um), length_(corr_length_um) {
    require_representable_length(sigma_h_um, "sigma_h");
    require_representable_length(corr_length_um, "correlation length");
}

double GaussianAcv::psd_unit(double zeta) const {
    return length_ * length_ / (4.0 * kPi) * std::exp(-0.25 * length_ * length_ * zeta * zeta);
}

double GaussianAcv::acv_normalized(double r) const { return std::exp(-r * r / (length_ * length_)); }

double GaussianAcv::radial_cdf(double zeta) const {
    if (std::isinf(zeta)) return 1.0;
    return -std::expm1(-0.25 * length_ * length_ * zeta * zeta);
}

double GaussianAcv::inverse_radial_cdf(double u) const {
    if (u <= 0.0) return 0.0;
    if (u >= 1.0) return kInf;
    return 2.0 * std::sqrt(-std::log1p(-u)) / length_;
}

std::string GaussianAcv::cache_key() const {
    return fmt::format("gauss(l={:.17g})", length_);
}

double GaussianAcv::mean_square_slope(double smoothing_um, double cutoff_zeta) const {
    require_non_negative(smoothing_um, "smoothing scale");
    if (!(cutoff_zeta > 0.0)) fail("cutoff frequency must be > 0 (or +inf for none), got {}", cutoff_zeta);
    // (l^2/2) int_0^{zc} zeta^3 e^{-a zeta^2} d zeta, a = l^2/4 + s^2.
    const double a = 0.25 * length_ * length_ + smoothing_um * smoothing_um;
    const double t = std::isinf(cutoff_zeta) ? kInf : a * cutoff_zeta * cutoff_zeta;
    const double bracket = std::isinf(t) ? 1.0 : -std::expm1(-t) - t * std::exp(-t);
    return sigma_ * sigma_ * length_ * length_ / (4.0 * a * a) * bracket;
}

// ---------------------------------------------------------------------------------------------------------------
AbcParameters to_abc(const KCorrelation& kc) {
    const double b = 2.0 * kPi * kc.correlation_length();
    return {kc.sigma_h() * kc.sigma_h() * b * b * (kc.gamma() - 1.0) / (2.0 * kPi), b, kc.gamma()};
}

KCorrelation from_abc(const AbcParameters& abc) {
    require_positive(abc.a, "ABC parameter A");
    require_positive(abc.b, "ABC parameter B");
    if (!(abc.c > 1.0)) fail("ABC parameter C must be > 1, got {}", abc.c);
    const double sigma2 = abc.a * 2.0 * kPi / (abc.b * abc.b * (abc.c - 1.0));
    return KCorrelation(std::sqrt(sigma2), abc.b / (2.0 * kPi), abc.c);
}

}  // namespace surfscatter::surface
