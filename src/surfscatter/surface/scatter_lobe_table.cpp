#include "surfscatter/surface/scatter_lobe_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/radial_table.hpp"

namespace surfscatter::surface {

namespace {
constexpr int kNodesPerDecade = 48;
const double kLogGMin = std::log(ScatterLobeTable::kMinG);
const double kGStep = std::log(10.0) / kNodesPerDecade;
const int kGNodes = static_cast<int>(std::lround((std::log(ScatterLobeTable::kMaxG) - kLogGMin) / kGStep)) + 1;

double node_g(int k) { return std::exp(kLogGMin + k * kGStep); }

// exp(-g (1 - rho)) - exp(-g), written to keep relative accuracy for small g.
double lobe_integrand(double g, double rho) {
    if (g < 30.0) return std::exp(-g) * std::expm1(g * rho);
    return std::exp(-g * (1.0 - rho)) - std::exp(-g);
}
}  // namespace

struct ScatterLobeTable::Data {
    std::shared_ptr<const detail::RadialFamily> family;  // row 0: g -> 0 limit (P-hat); row k >= 1: g = node_g(k - 1)
};

namespace {

detail::RadialFamily build(const RadialStatistics& stats) {
    detail::RadialFamily family;
    const detail::TransformSetup setup = detail::make_transform_setup(stats, ScatterLobeTable::kMaxG);
    family.grid = detail::stored_grid(setup);
    family.set_base(stats);
    family.rows.push_back(detail::make_row(setup, setup.rho, 1.0, 1.0, family.grid));
    std::vector<double> f(setup.rho.size());
    for (int k = 0; k < kGNodes; ++k) {
        const double g = node_g(k);
        for (std::size_t j = 0; j < f.size(); ++j) f[j] = lobe_integrand(g, setup.rho[j]);
        family.rows.push_back(detail::make_row(setup, f, -std::expm1(-g), g, family.grid));
    }
    return family;
}

void check_g(double g) {
    if (!(g >= 0.0 && g <= ScatterLobeTable::kMaxG)) fail("lobe parameter g = {} outside [0, {}]", g, ScatterLobeTable::kMaxG);
}

// Cubic Lagrange weights over rows (first .. first+3) for the fractional node position t.
struct Stencil {
    int first;
    std::array<double, 4> w;
};
Stencil stencil(double g) {
    const double t = (std::log(g) - kLogGMin) / kGStep;
    int i = std::clamp(static_cast<int>(std::floor(t)), 1, kGNodes - 3);
    const double u = t - i;
    return {i,  // rows i .. i+3 hold nodes i-1 .. i+2 (row 0 is the g -> 0 limit)
            {-u * (u - 1.0) * (u - 2.0) / 6.0, (u + 1.0) * (u - 1.0) * (u - 2.0) / 2.0,
             -(u + 1.0) * u * (u - 2.0) / 2.0, (u + 1.0) * u * (u - 1.0) / 6.0}};
}

}  // namespace

ScatterLobeTable::ScatterLobeTable(std::shared_ptr<const Data> data) : data_(std::move(data)) {}

std::shared_ptr<const ScatterLobeTable> ScatterLobeTable::get(const RadialStatistics& stats) {
    const std::string key = fmt::format("lobe:{}:g={}..{}x{}", stats.cache_key(), kMinG, kMaxG, kNodesPerDecade);
    auto family = detail::cached_family(key, kGNodes + 1, [&] { return build(stats); });
    return std::make_shared<const ScatterLobeTable>(std::make_shared<const Data>(Data{std::move(family)}));
}

double ScatterLobeTable::shape(double g, double zeta) const {
    check_g(g);
    const detail::RadialFamily& f = *data_->family;
    if (!(zeta >= 0.0) || std::isinf(zeta)) return 0.0;
    const double log_zeta = zeta > 0.0 ? std::log(zeta) : -1e300;
    if (g < kMinG) {
        // Linear in g between the g -> 0 limit and the first node (error O(g^2)).
        const double s0 = zeta > 0.0 ? std::exp(f.log_value(0, log_zeta)) : f.value(0, 0.0);
        const double s1 = zeta > 0.0 ? std::exp(f.log_value(1, log_zeta)) : f.value(1, 0.0);
        return s0 + (g / kMinG) * (s1 - s0);
    }
    const Stencil s = stencil(g);
    double log_value = 0.0;
    for (int i = 0; i < 4; ++i)
        log_value += s.w[i] * (zeta > 0.0 ? f.log_value(s.first + i, log_zeta) : f.rows[s.first + i].log_value.front());
    return std::exp(log_value);
}

double ScatterLobeTable::eval(double g, double zeta) const {
    check_g(g);
    if (g == 0.0) return 0.0;
    return -std::expm1(-g) * shape(g, zeta);
}

double ScatterLobeTable::radial_cdf(double g, double zeta) const {
    check_g(g);
    const detail::RadialFamily& f = *data_->family;
    if (g < kMinG) return std::clamp(f.cdf(0, zeta) + (g / kMinG) * (f.cdf(1, zeta) - f.cdf(0, zeta)), 0.0, 1.0);
    const Stencil s = stencil(g);
    double c = 0.0;
    for (int i = 0; i < 4; ++i) c += s.w[i] * f.cdf(s.first + i, zeta);
    return std::clamp(c, 0.0, 1.0);
}

double ScatterLobeTable::inverse_radial_cdf(double g, double u) const {
    check_g(g);
    if (!(u > 0.0)) return 0.0;
    u = std::min(u, 1.0 - 1e-16);
    const detail::RadialFamily& f = *data_->family;
    // Bracket from the neighbouring rows' node intervals, then bisection in ln zeta on the interpolated CDF.
    double a = 1e300, b = -1e300;
    const int first = g < kMinG ? 0 : stencil(g).first;
    for (int i = 0; i < (g < kMinG ? 2 : 4); ++i) {
        double lo, hi;
        f.bracket(first + i, u, lo, hi);
        a = std::min(a, lo);
        b = std::max(b, hi);
    }
    a -= 0.05;
    b += 0.05;
    for (int it = 0; it < 40 && radial_cdf(g, std::exp(a)) > u; ++it) a -= 1.0;
    for (int it = 0; it < 40 && radial_cdf(g, std::exp(b)) < u; ++it) b += 1.0;
    for (int it = 0; it < 48; ++it) {
        const double mid = 0.5 * (a + b);
        (radial_cdf(g, std::exp(mid)) < u ? a : b) = mid;
    }
    return std::exp(0.5 * (a + b));
}

}  // namespace surfscatter::surface
