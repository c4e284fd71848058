#include "surfscatter/surface/refit.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"

namespace surfscatter::surface {
namespace {

constexpr int kFitPoints = 400;

struct Sampled {
    std::vector<double> zeta, log_value, weight;  // weight = mass element P zeta^2 d(ln zeta) (times 2 pi)
    double step = 0;
};

Sampled sample_order(const SelfConvolutionTable& table, int m) {
    Sampled s;
    const double lo = std::log(table.inverse_radial_cdf(m, 1e-6)), hi = std::log(table.inverse_radial_cdf(m, 1.0 - 1e-6));
    s.step = (hi - lo) / (kFitPoints - 1);
    for (int j = 0; j < kFitPoints; ++j) {
        const double z = std::exp(lo + j * s.step);
        const double p = table.eval(m, z);
        s.zeta.push_back(z);
        s.log_value.push_back(std::log(p));
        s.weight.push_back(2.0 * kPi * z * z * p * s.step);
    }
    return s;
}

double objective(const Sampled& s, double gamma, double log_length) {
    const KCorrelation kc(1.0, std::exp(log_length), gamma);
    double sum = 0.0;
    for (std::size_t j = 0; j < s.zeta.size(); ++j) {
        const double d = s.log_value[j] - std::log(kc.psd_unit(s.zeta[j]));
        sum += s.weight[j] * d * d;
    }
    return sum;
}

}  // namespace

void require_refit_orders(long long orders, const char* what) {
    if (orders < 1 || orders > kMaxRefitOrders) fail("{} must be in [1, {}], got {}", what, kMaxRefitOrders, orders);
}

RefitResult refit_self_convolutions(const KCorrelation& kc, int max_order) {
    if (max_order < 1) fail("refit needs at least one order, got {}", max_order);
    const auto table = SelfConvolutionTable::get(kc, max_order);
    const double l = kc.correlation_length();
    RefitResult result;
    double num = 0.0, den = 0.0;
    for (int m = 1; m <= max_order; ++m) {
        const Sampled s = sample_order(*table, m);
        // Golden-section search on ln L_m (the objective is unimodal in ln L_m).
        double a = std::log(l) - 12.0, b = std::log(l) + 2.0;
        const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
        double x1 = b - ratio * (b - a), x2 = a + ratio * (b - a);
        double f1 = objective(s, kc.gamma(), x1), f2 = objective(s, kc.gamma(), x2);
        for (int it = 0; it < 120; ++it) {
            if (f1 < f2) {
                b = x2, x2 = x1, f2 = f1;
                x1 = b - ratio * (b - a);
                f1 = objective(s, kc.gamma(), x1);
            } else {
                a = x1, x1 = x2, f1 = f2;
                x2 = a + ratio * (b - a);
                f2 = objective(s, kc.gamma(), x2);
            }
        }
        const double length_m = std::exp(0.5 * (a + b));
        const KCorrelation fit(1.0, length_m, kc.gamma());
        double misfit = 0.0;
        for (std::size_t j = 0; j < s.zeta.size(); ++j)
            misfit += std::abs(fit.psd_unit(s.zeta[j]) - std::exp(s.log_value[j])) * 2.0 * kPi * s.zeta[j] * s.zeta[j] * s.step;
        result.corr_length_m.push_back(length_m);
        result.misfit_m.push_back(misfit);
        // Power law through L at m = 1: least squares of ln(L_m / L) = -x ln m.
        const double lm = std::log(static_cast<double>(m));
        num += lm * std::log(length_m / l);
        den += lm * lm;
    }
    result.exponent_x = den > 0.0 ? -num / den : 0.0;
    return result;
}

}  // namespace surfscatter::surface
