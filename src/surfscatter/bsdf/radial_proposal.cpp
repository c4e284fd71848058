#include "surfscatter/bsdf/radial_proposal.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/math/fast_math.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr int kNodes = 256;
constexpr std::size_t kCells = 1024;
constexpr double kLogitRange = 23.0;  // u from 1e-10 to 1 - 1e-10

// Cubic Hermite on t in [0, 1]: value and derivative (d/dt) from end values f0, f1 and end derivatives m0, m1 (d/dt).
double hermite(double t, double f0, double f1, double m0, double m1) {
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * f0 + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * f1 + (t3 - t2) * m1;
}
double hermite_derivative(double t, double f0, double f1, double m0, double m1) {
    const double t2 = t * t;
    return (6 * t2 - 6 * t) * f0 + (3 * t2 - 4 * t + 1) * m0 + (-6 * t2 + 6 * t) * f1 + (3 * t2 - 2 * t) * m1;
}

}  // namespace

RadialProposal::RadialProposal(const std::function<double(double)>& cdf, const std::function<double(double)>& inverse,
                               const std::function<double(double)>& density_2d) {
    for (int j = 0; j < kNodes; ++j) {
        const double t = -kLogitRange + 2.0 * kLogitRange * j / (kNodes - 1);
        const double zeta = inverse(1.0 / (1.0 + std::exp(-t)));
        if (!(zeta > 0) || !std::isfinite(zeta)) continue;
        const double lz = std::log(zeta);
        const double c = std::clamp(cdf(zeta), 0.0, 1.0);
        if (!log_zeta_.empty() && (lz <= log_zeta_.back() + 1e-9 || c <= cdf_.back())) continue;  // strictly increasing
        log_zeta_.push_back(lz);
        cdf_.push_back(c);
        slope_.push_back(std::max(0.0, kTwoPi * zeta * zeta * density_2d(zeta)));
    }
    // The nodes carry 1 - tail_mass of the mass, the power-law tail the rest.
    tail_mass_ = std::clamp(1.0 - cdf_.back(), 1e-12, 1e-3);
    const double scale = (1.0 - tail_mass_) / cdf_.back();
    for (std::size_t j = 0; j < cdf_.size(); ++j) {
        cdf_[j] *= scale;
        slope_[j] *= scale;
    }
    tail_power_ = std::clamp(slope_.back() / tail_mass_, 0.5, 8.0);
    zeta_front_ = std::exp(log_zeta_.front());
    // Segment index at the start of each of kCells uniform cells in ln zeta (replaces a branchy binary search).
    const double width = (log_zeta_.back() - log_zeta_.front()) / kCells;
    inverse_cell_ = 1.0 / width;
    for (std::size_t c = 0, j = 0; c < kCells; ++c) {
        while (j + 2 < log_zeta_.size() && log_zeta_[j + 1] <= log_zeta_.front() + static_cast<double>(c) * width) ++j;
        cell_start_.push_back(static_cast<std::uint16_t>(j));
    }
    // Fritsch-Carlson: limit the node slopes so that every cubic segment is monotone.
    for (std::size_t j = 0; j + 1 < cdf_.size(); ++j) {
        const double secant = (cdf_[j + 1] - cdf_[j]) / (log_zeta_[j + 1] - log_zeta_[j]);
        const double a = slope_[j] / secant, b = slope_[j + 1] / secant;
        const double r = a * a + b * b;
        if (r > 9.0) {
            const double tau = 3.0 / std::sqrt(r);
            slope_[j] = tau * a * secant;
            slope_[j + 1] = tau * b * secant;
        }
    }
}

// Last node <= lz, for lz inside (front, back): from the node at the start of lz's cell, a step or two up.
std::size_t RadialProposal::segment(double lz) const {
    const auto cell = std::min(std::size_t((lz - log_zeta_.front()) * inverse_cell_), cell_start_.size() - 1);
    std::size_t j = cell_start_[cell];
    while (log_zeta_[j + 1] <= lz) ++j;
    return j;
}

double RadialProposal::cdf(double zeta) const {
    if (!(zeta > 0)) return 0.0;
    const double lz = math::fast_log(zeta);
    if (lz <= log_zeta_.front()) return cdf_.front() * std::exp(2.0 * (lz - log_zeta_.front()));
    if (lz >= log_zeta_.back()) return 1.0 - tail_mass_ * std::exp(-tail_power_ * (lz - log_zeta_.back()));
    const std::size_t j = segment(lz);
    const double h = log_zeta_[j + 1] - log_zeta_[j];
    return hermite((lz - log_zeta_[j]) / h, cdf_[j], cdf_[j + 1], slope_[j] * h, slope_[j + 1] * h);
}

double RadialProposal::inverse(double u) const {
    if (!(u > 0)) return 0.0;
    if (u <= cdf_.front()) return std::exp(log_zeta_.front()) * std::sqrt(u / cdf_.front());
    if (u >= cdf_.back()) {
        if (u >= 1.0) return std::numeric_limits<double>::infinity();
        return std::exp(log_zeta_.back() - std::log((1.0 - u) / tail_mass_) / tail_power_);
    }
    const auto j = std::size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u) - cdf_.begin()) - 1;
    const double h = log_zeta_[j + 1] - log_zeta_[j];
    const double f0 = cdf_[j], f1 = cdf_[j + 1], m0 = slope_[j] * h, m1 = slope_[j + 1] * h;
    // Safeguarded Newton on the monotone cubic: bisection bracket [lo, hi] in t.
    double lo = 0, hi = 1, t = (u - f0) / (f1 - f0);
    for (int it = 0; it < 60; ++it) {
        const double f = hermite(t, f0, f1, m0, m1) - u;
        if (f > 0) hi = t; else lo = t;
        const double d = hermite_derivative(t, f0, f1, m0, m1);
        double next = d > 0 ? t - f / d : 0.5 * (lo + hi);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - t) < 1e-15) {
            t = next;
            break;
        }
        t = next;
    }
    return std::exp(log_zeta_[j] + t * h);
}

double RadialProposal::density_2d(double zeta) const {
    if (!(zeta >= 0)) return 0.0;
    if (zeta <= zeta_front_) return cdf_.front() / (kPi * zeta_front_ * zeta_front_);
    const double lz = math::fast_log(zeta);
    if (lz >= log_zeta_.back())
        return tail_power_ * tail_mass_ * std::exp(-tail_power_ * (lz - log_zeta_.back())) / (kTwoPi * zeta * zeta);
    const std::size_t j = segment(lz);
    const double h = log_zeta_[j + 1] - log_zeta_[j];
    const double dF_dlnzeta =
        hermite_derivative((lz - log_zeta_[j]) / h, cdf_[j], cdf_[j + 1], slope_[j] * h, slope_[j + 1] * h) / h;
    return std::max(0.0, dF_dlnzeta) / (kTwoPi * zeta * zeta);
}

}  // namespace surfscatter::bsdf
