#include "surfscatter/bsdf/poisson.hpp"

#include <algorithm>
#include <cmath>

namespace surfscatter::bsdf {

double poisson_pmf(int m, double mean) {
    if (m < 0) return 0.0;
    if (mean <= 0) return m == 0 ? 1.0 : 0.0;
    return std::exp(m * std::log(mean) - mean - std::lgamma(m + 1.0));
}

PoissonWindow::PoissonWindow(double mean, int first, int last, double first_factor, double last_factor)
    : first_(std::max(0, first)) {
    last = std::max(last, first_);
    weights_.resize(last - first_ + 1);
    // pmf(first) in log space, then the ratio pmf(m+1)/pmf(m) = mean/(m+1); restarted in log space if it underflows.
    for (int m = first_; m <= last; ++m) {
        const double prev = m > first_ ? weights_[m - first_ - 1] : 0.0;
        weights_[m - first_] = prev > 1e-280 ? prev * mean / m : poisson_pmf(m, mean);
    }
    weights_.front() *= first_factor;
    weights_.back() *= last_factor;
    kept_mass_ = 0;
    for (double w : weights_) kept_mass_ += w;
    cdf_.resize(weights_.size());
    double running = 0;
    for (std::size_t i = 0; i < weights_.size(); ++i) {
        // An all-underflow window (mean far from it) degenerates to its nearest order.
        weights_[i] = kept_mass_ > 0 ? weights_[i] / kept_mass_
                                     : (mean < first_ ? (i == 0 ? 1.0 : 0.0) : (i + 1 == weights_.size() ? 1.0 : 0.0));
        running += weights_[i];
        cdf_[i] = running;
    }
    cdf_.back() = 1.0;
}

PoissonWindow PoissonWindow::within_sigmas(double mean, double sigmas, int first_min) {
    const double sd = std::sqrt(mean), lo = mean - sigmas * sd, hi = mean + sigmas * sd;
    // first_min is always kept whole; an edge order beyond it enters with its fraction inside [lo, hi].
    const int lo_order = int(std::floor(lo)), first = std::max(first_min, lo_order);
    const int hi_order = int(std::ceil(hi)), last = std::max(first, hi_order);
    const double first_factor = lo_order >= first_min ? 1.0 + first - lo : 1.0;
    const double last_factor = hi_order > first ? 1.0 + hi - last : 1.0;
    return PoissonWindow(mean, first, last, first_factor, last_factor);
}

PoissonWindow PoissonWindow::by_mass(double mean, double epsilon, int first_min) {
    // Grow from the mode both ways, always adding the larger neighbour, until the remaining mass < epsilon.
    const double above_min = [&] {
        double below = 0;
        for (int m = 0; m < first_min; ++m) below += poisson_pmf(m, mean);
        return 1.0 - below;
    }();
    int lo = std::max(first_min, int(std::floor(mean))), hi = lo;
    double mass = poisson_pmf(lo, mean);
    const int cap = int(mean + 40.0 * std::sqrt(mean) + 60.0);
    while (mass < above_min * (1.0 - epsilon) && hi < cap) {
        const double down = lo > first_min ? poisson_pmf(lo - 1, mean) : -1.0;
        const double up = poisson_pmf(hi + 1, mean);
        if (down > up) {
            --lo;
            mass += down;
        } else {
            ++hi;
            mass += up;
        }
    }
    return PoissonWindow(mean, lo, hi);
}

double PoissonWindow::weight(int m) const {
    if (m < first_ || m > last()) return 0.0;
    return weights_[m - first_];
}

int PoissonWindow::sample(double u) const {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    return first_ + int(std::min<std::ptrdiff_t>(it - cdf_.begin(), std::ptrdiff_t(cdf_.size()) - 1));
}

int sample_poisson(double mean, double u) {
    const double span = 9.0 * std::sqrt(mean) + 12.0;
    return PoissonWindow(mean, int(std::floor(mean - span)), int(std::ceil(mean + span))).sample(u);
}

}  // namespace surfscatter::bsdf
