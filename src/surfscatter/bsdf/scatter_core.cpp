#include "surfscatter/bsdf/scatter_core.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "surfscatter/bsdf/poisson.hpp"
#include "surfscatter/math/fast_math.hpp"

namespace surfscatter::bsdf {

// --- exact ---------------------------------------------------------------------------------------------------

namespace {
constexpr double kProposalsPerDecade = 16.0;
const int kFirstProposal = int(std::lround(kProposalsPerDecade * std::log10(surface::ScatterLobeTable::kMinG)));
const int kLastProposal = int(std::lround(kProposalsPerDecade * std::log10(surface::ScatterLobeTable::kMaxG)));
}  // namespace

ExactScatterCore::ExactScatterCore(std::shared_ptr<const surface::RadialStatistics> stats)
    : table_(surface::ScatterLobeTable::get(std::move(stats))), proposals_(std::size_t(kLastProposal - kFirstProposal + 1)) {}

double ExactScatterCore::density(double g, double zeta) const {
    return table_->eval(std::min(g, surface::ScatterLobeTable::kMaxG), zeta);
}

const RadialProposal& ExactScatterCore::proposal(double g_star) const {
    const double g_min = surface::ScatterLobeTable::kMinG;
    const double log_g = math::fast_log(std::clamp(g_star, g_min, surface::ScatterLobeTable::kMaxG));
    // Nearest node, rounding by truncation of a positive number (lround is a libm call).
    const int node = int(kProposalsPerDecade / std::numbers::ln10 * log_g - kFirstProposal + 0.5) + kFirstProposal;
    return proposals_.get(std::size_t(node - kFirstProposal), [&] {
        const double g = std::pow(10.0, node / kProposalsPerDecade);
        return RadialProposal([&](double z) { return table_->radial_cdf(g, z); },
                              [&](double u) { return table_->inverse_radial_cdf(g, u); },
                              [&](double z) { return table_->shape(g, z); });
    });
}

double ExactScatterCore::sample_radius(double g_star, double zeta_max, double, double u) const {
    const RadialProposal& p = proposal(g_star);
    return std::min(zeta_max, p.inverse(u * p.cdf(zeta_max)));
}

double ExactScatterCore::sample_density(double g_star, double zeta_max, double zeta) const {
    if (zeta > zeta_max) return 0.0;
    const RadialProposal& p = proposal(g_star);
    const double f_max = p.cdf(zeta_max);
    return f_max > 0 ? p.density_2d(zeta) / f_max : 0.0;
}

// --- refit ---------------------------------------------------------------------------------------------------

RefitScatterCore::RefitScatterCore(const surface::KCorrelation& kc, double exponent_x, Truncation truncation,
                                   double epsilon)
    : length_(kc.correlation_length()), gamma_(kc.gamma()), exponent_x_(exponent_x), truncation_(truncation),
      epsilon_(epsilon) {
    orders_.reserve(kOrders);
    for (int m = 1; m <= kOrders; ++m) orders_.emplace_back(1.0, order_length(m), gamma_);
}

surface::KCorrelation RefitScatterCore::order_statistics(int m) const {
    return m <= kOrders ? orders_[m - 1] : surface::KCorrelation(1.0, order_length(m), gamma_);
}

std::string RefitScatterCore::cache_key() const {
    return fmt::format("refit(L={:.17g},gamma={:.17g},x={:.17g},{},epsilon={:.17g})", length_, gamma_, exponent_x_,
                       to_string(truncation_), epsilon_);
}

double RefitScatterCore::order_length(int m) const { return length_ * std::pow(double(m), -exponent_x_); }

PoissonWindow RefitScatterCore::window(double g) const {
    return truncation_ == Truncation::three_sigma ? PoissonWindow::within_sigmas(g, 3.0, 1)
                                                  : PoissonWindow::by_mass(g, epsilon_, 1);
}

double RefitScatterCore::density(double g, double zeta) const {
    if (!(g > 0)) return 0.0;
    const PoissonWindow w = window(g);
    double sum = 0;
    for (int m = w.first(); m <= w.last(); ++m)
        sum += w.weight(m) * w.kept_mass() * order_statistics(m).psd_unit(zeta);
    return sum;
}

double RefitScatterCore::sample_radius(double g_star, double zeta_max, double u_order, double u) const {
    const surface::KCorrelation kc = order_statistics(window(g_star).sample(u_order));
    return std::min(zeta_max, kc.inverse_radial_cdf(u * kc.radial_cdf(zeta_max)));
}

double RefitScatterCore::sample_density(double g_star, double zeta_max, double zeta) const {
    if (zeta > zeta_max) return 0.0;
    const PoissonWindow w = window(g_star);
    double sum = 0;
    for (int m = w.first(); m <= w.last(); ++m) {
        const surface::KCorrelation kc = order_statistics(m);
        sum += w.weight(m) * kc.psd_unit(zeta) / kc.radial_cdf(zeta_max);
    }
    return sum;
}

// --- first order ---------------------------------------------------------------------------------------------

FirstOrderCore::FirstOrderCore(std::shared_ptr<const surface::RadialStatistics> stats, SsaForm form)
    : stats_(std::move(stats)), form_(form) {}

std::string FirstOrderCore::cache_key() const {
    return fmt::format("first-order({},{})", stats_->cache_key(), to_string(form_));
}

double FirstOrderCore::density(double g, double zeta) const {
    const double weight = form_ == SsaForm::strict ? g : math::one_minus_exp(g);
    return weight * stats_->psd_unit(zeta);
}

double FirstOrderCore::sample_radius(double, double zeta_max, double, double u) const {
    return std::min(zeta_max, inverse_radial_cdf(*stats_, u * stats_->radial_cdf(zeta_max)));
}

double FirstOrderCore::sample_density(double, double zeta_max, double zeta) const {
    if (zeta > zeta_max) return 0.0;
    const double f_max = stats_->radial_cdf(zeta_max);
    return f_max > 0 ? stats_->psd_unit(zeta) / f_max : 0.0;
}

double inverse_radial_cdf(const surface::RadialStatistics& stats, double u) {
    if (const auto* kc = dynamic_cast<const surface::KCorrelation*>(&stats)) return kc->inverse_radial_cdf(u);
    if (const auto* gauss = dynamic_cast<const surface::GaussianAcv*>(&stats)) return gauss->inverse_radial_cdf(u);
    if (u <= 0) return 0.0;
    // Bisection in log(zeta) after bracketing around the correlation length.
    double lo = 1e-12 / stats.correlation_length(), hi = 1.0 / stats.correlation_length();
    while (stats.radial_cdf(hi) < u && hi < 1e12) hi *= 4.0;
    if (stats.radial_cdf(lo) >= u) return lo;
    for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-13; ++i) {
        const double mid = std::sqrt(lo * hi);
        (stats.radial_cdf(mid) < u ? lo : hi) = mid;
    }
    return std::sqrt(lo * hi);
}

}  // namespace surfscatter::bsdf
