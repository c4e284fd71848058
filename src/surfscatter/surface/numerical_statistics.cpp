#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/hankel.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {
namespace {
constexpr int kPointsPerDecade = 256;
constexpr double kDecadesBelow = 10.0, kDecadesAbove = 12.0;  // transform range around the support hints
}  // namespace

void NumericalRadialStatistics::initialise(std::string key) {
    key_ = std::move(key);
    if (!(zeta_lo_ > 0.0 && zeta_hi_ > zeta_lo_)) fail("PSD support hints must satisfy 0 < lo < hi, got {}..{}", zeta_lo_, zeta_hi_);
    // sigma^2 = int P 2 pi zeta d zeta: flat part below zeta_lo plus quadrature in ln zeta up to far beyond zeta_hi.
    auto mass_density = [&](double y) {
        const double z = std::exp(y);
        return 2.0 * kPi * z * z * psd_raw(z);
    };
    const double y_lo = std::log(zeta_lo_), y_hi = std::log(zeta_hi_);
    const double below = kPi * zeta_lo_ * zeta_lo_ * psd_raw(zeta_lo_ * 1e-6);
    const double inside = math::integrate_adaptive(mass_density, y_lo, y_hi, 1e-11);
    const double above = math::integrate_adaptive(mass_density, y_hi, y_hi + kDecadesAbove * std::log(10.0), 1e-11);
    const double sigma2 = below + inside + above;
    if (!(sigma2 > 0.0) || !std::isfinite(sigma2)) fail("PSD has no finite positive mass (sigma^2 = {})", sigma2);
    sigma_ = std::sqrt(sigma2);

    // Radial CDF on a log grid (4-point cumulative rule in ln zeta).
    const double step = std::log(10.0) / kPointsPerDecade;
    const double y0 = y_lo - kDecadesBelow * std::log(10.0);
    const int n = static_cast<int>((y_hi + kDecadesAbove * std::log(10.0) - y0) / step) + 1;
    log_zeta_.resize(n);
    cdf_.resize(n);
    std::vector<double> density(n);
    for (int j = 0; j < n; ++j) {
        log_zeta_[j] = y0 + j * step;
        density[j] = mass_density(log_zeta_[j]) / sigma2;
    }
    double cumulative = kPi * std::exp(2.0 * y0) * psd_raw(std::exp(y0)) / sigma2;
    for (int j = 0; j < n; ++j) {
        cdf_[j] = cumulative;
        if (j + 1 < n) {
            const double a = density[std::max(j - 1, 0)], b = density[j], c = density[j + 1],
                         d = density[std::min(j + 2, n - 1)];
            cumulative += step * (-a + 13.0 * b + 13.0 * c - d) / 24.0;
        }
    }
    // The rule's own total is 1 to ~1e-9 for smooth PSDs, less where it steps across a kink (a measured PSD's
    // roll-off at Nyquist: 1e-5): normalise by it so that the CDF ends at 1.
    for (double& c : cdf_) c = std::min(c / cdf_.back(), 1.0);
    // Length scale: inverse of the median radius of P-hat.
    const auto median = std::lower_bound(cdf_.begin(), cdf_.end(), 0.5) - cdf_.begin();
    length_ = 1.0 / std::exp(log_zeta_[std::min<std::ptrdiff_t>(median, n - 1)]);

    // rho = 2 pi H0{P-hat} on a log r grid (rho(0) = 1 holds through the exact sigma^2 above).
    const FftLogHankel hankel(std::exp(y0), std::exp(y0) * std::pow(10.0, std::ceil((n - 1) / double(kPointsPerDecade))),
                              2 * ((n + 1) / 2));
    std::vector<double> phat(hankel.size());
    for (int j = 0; j < hankel.size(); ++j) phat[j] = psd_raw(hankel.r(j)) / sigma2;
    std::vector<double> rho = hankel.transform(phat);
    log_r_.resize(hankel.size());
    rho_.resize(hankel.size());
    const int first = 4 * kPointsPerDecade;  // skip the ringing ends
    for (int j = 0; j < hankel.size(); ++j) {
        log_r_[j] = std::log(hankel.zeta(j));
        rho_[j] = 2.0 * kPi * rho[j];
    }
    r_valid_lo_ = log_r_[first];
    r_valid_hi_ = log_r_[hankel.size() - 1 - first];
}

double NumericalRadialStatistics::acv_normalized(double r) const {
    if (!(r > 0.0)) return 1.0;
    const double y = std::log(r);
    const int n = static_cast<int>(rho_.size());
    const double step = log_r_[1] - log_r_[0];
    if (y >= r_valid_hi_) return 0.0;
    // Below the transform's reliable range rho is 1 to within its accuracy.
    if (y <= r_valid_lo_) return 1.0;
    return std::clamp(cubic_interpolate(rho_.data(), n, (y - log_r_[0]) / step), -1.0, 1.0);
}

double NumericalRadialStatistics::radial_cdf(double zeta) const {
    if (!(zeta > 0.0)) return 0.0;
    if (std::isinf(zeta)) return 1.0;
    const double y = std::log(zeta);
    const int n = static_cast<int>(cdf_.size());
    const double step = log_zeta_[1] - log_zeta_[0];
    if (y <= log_zeta_[0]) return kPi * zeta * zeta * psd_unit(zeta);
    if (y >= log_zeta_[n - 1]) return 1.0;
    return std::clamp(cubic_interpolate(cdf_.data(), n, (y - log_zeta_[0]) / step), 0.0, 1.0);
}

// ---------------------------------------------------------------------------------------------------------------
TabulatedPsd::TabulatedPsd(std::vector<double> zeta, std::vector<double> psd) {
    if (zeta.size() != psd.size()) fail("tabulated PSD: {} frequencies but {} values", zeta.size(), psd.size());
    if (zeta.size() < 4) fail("tabulated PSD needs at least 4 samples, got {}", zeta.size());
    for (std::size_t i = 0; i < zeta.size(); ++i) {
        if (!(zeta[i] > 0.0) || !std::isfinite(zeta[i])) fail("tabulated PSD: frequency #{} = {} is not positive", i + 1, zeta[i]);
        if (!(psd[i] > 0.0) || !std::isfinite(psd[i])) fail("tabulated PSD: value #{} = {} is not positive", i + 1, psd[i]);
        if (i > 0 && !(zeta[i] > zeta[i - 1])) fail("tabulated PSD: frequencies must increase (#{} = {})", i + 1, zeta[i]);
        log_zeta_samples_.push_back(std::log(zeta[i]));
        log_psd_samples_.push_back(std::log(psd[i]));
    }
    // Tail slope: least squares over the samples of the last decade (at least the last two).
    const double y_end = log_zeta_samples_.back();
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int count = 0;
    for (std::size_t i = 0; i < zeta.size(); ++i) {
        if (log_zeta_samples_[i] < y_end - std::log(10.0) && i + 2 < zeta.size()) continue;
        sx += log_zeta_samples_[i];
        sy += log_psd_samples_[i];
        sxx += log_zeta_samples_[i] * log_zeta_samples_[i];
        sxy += log_zeta_samples_[i] * log_psd_samples_[i];
        ++count;
    }
    tail_slope_ = (count * sxy - sx * sy) / (count * sxx - sx * sx);
    if (!(tail_slope_ < -2.0)) fail("tabulated PSD tail falls as zeta^{:.3g}; it must fall faster than zeta^-2", tail_slope_);
    zeta_lo_ = zeta.front();
    zeta_hi_ = zeta.back();
    std::string key = "tab(";
    for (std::size_t i = 0; i < zeta.size(); ++i) key += fmt::format("{:.17g}:{:.17g};", zeta[i], psd[i]);
    initialise(key + ")");
}

double TabulatedPsd::psd_raw(double zeta) const {
    const double y = std::log(zeta);
    if (y <= log_zeta_samples_.front()) return std::exp(log_psd_samples_.front());
    if (y >= log_zeta_samples_.back()) return std::exp(log_psd_samples_.back() + tail_slope_ * (y - log_zeta_samples_.back()));
    const std::size_t i = std::upper_bound(log_zeta_samples_.begin(), log_zeta_samples_.end(), y) - log_zeta_samples_.begin();
    const double t = (y - log_zeta_samples_[i - 1]) / (log_zeta_samples_[i] - log_zeta_samples_[i - 1]);
    return std::exp(log_psd_samples_[i - 1] + t * (log_psd_samples_[i] - log_psd_samples_[i - 1]));
}

}  // namespace surfscatter::surface
