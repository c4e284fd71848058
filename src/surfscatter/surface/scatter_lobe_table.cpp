#include "surfscatter/surface/scatter_lobe_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/surface/radial_table.hpp"

namespace surfscatter::surface {

namespace {
constexpr int kNodesPerDecade = 48;
const double kLogGMin = std::log(ScatterLobeTable::kMinG);
const double kLogGMax = std::log(ScatterLobeTable::kMaxG);
const double kGStep = std::log(10.0) / kNodesPerDecade;
const double kInvGStep = 1.0 / kGStep;  // lookups multiply: a division costs as much as the rest of the stencil
constexpr double kInverseTolerance = 1e-13;  // of inverse_radial_cdf, in ln zeta
const int kGNodes = static_cast<int>(std::lround((std::log(ScatterLobeTable::kMaxG) - kLogGMin) / kGStep)) + 1;

double node_g(int k) { return std::exp(kLogGMin + k * kGStep); }

// exp(-g (1 - rho)) - exp(-g), written to keep relative accuracy for small g.
double lobe_integrand(double g, double rho) {
    if (g < 30.0) return std::exp(-g) * std::expm1(g * rho);
    return std::exp(-g * (1.0 - rho)) - std::exp(-g);
}

// e^x - 1 - x without cancellation for small |x|.
double expm1_minus_x(double x) {
    if (std::abs(x) < 0.1) {
        double term = 0.5 * x * x, sum = term;
        for (int n = 3; n < 14; ++n) {
            term *= x / n;
            sum += term;
        }
        return sum;
    }
    return std::expm1(x) - x;
}

// The lobe less its first-order term, exp(-g (1 - rho)) - exp(-g) (1 + g rho): the orders m >= 2.
double remainder_integrand(double g, double rho) {
    if (g < 30.0) return std::exp(-g) * expm1_minus_x(g * rho);
    return std::exp(-g * (1.0 - rho)) - std::exp(-g) * (1.0 + g * rho);
}

// Mass of the orders m >= 2: 1 - e^{-g} - g e^{-g} (series below g = 0.1, where the difference cancels).
double remainder_mass(double g) {
    if (g < 0.1) {
        double term = -g, sum = 0.0;  // sum_{n>=2} (-1)^n g^n (n-1) / n!
        for (int n = 2; n < 16; ++n) {
            term *= -g / n;
            sum += (n - 1) * term;
        }
        return sum;
    }
    return -std::expm1(-g) - g * std::exp(-g);
}
}  // namespace

struct ScatterLobeTable::Data {
    // Row 0: g -> 0 limit of the tabulated shape; row k >= 1: g = node_g(k - 1). Continuous P-hat: the rows are the
    // whole lobe's shape s_g (row 0 = P-hat). P-hat with a jump (first_order set): the rows are the shape of the
    // orders m >= 2, whose mass is remainder_mass(g) (row 0 = P-hat^{*2}), and g e^{-g} P-hat is added exactly.
    std::shared_ptr<const detail::RadialFamily> family;
    std::shared_ptr<const RadialStatistics> first_order;
    std::string key;  // the family's cache key and format version
};

namespace {

// Rows of the whole lobe, or (first_order_apart) of its orders m >= 2. The tail weights are the asymptotic ratios to
// P-hat (P-hat^{*m} ~ m P-hat): g for S_g, g (1 - e^{-g}) for the orders m >= 2, 2 for P-hat^{*2}.
detail::RadialFamily build(const RadialStatistics& stats, bool first_order_apart) {
    detail::RadialFamily family;
    const detail::TransformSetup setup = detail::make_transform_setup(stats, ScatterLobeTable::kMaxG);
    family.grid = detail::stored_grid(setup);
    family.set_base(stats);
    std::vector<double> f(setup.rho.size());
    if (first_order_apart) {
        for (std::size_t j = 0; j < f.size(); ++j) f[j] = setup.rho[j] * setup.rho[j];
        family.rows.push_back(detail::make_row(setup, f, 1.0, 2.0, family.grid));
    } else {
        family.rows.push_back(detail::make_row(setup, setup.rho, 1.0, 1.0, family.grid));
    }
    for (int k = 0; k < kGNodes; ++k) {
        const double g = node_g(k);
        if (first_order_apart) {
            for (std::size_t j = 0; j < f.size(); ++j) f[j] = remainder_integrand(g, setup.rho[j]);
            family.rows.push_back(detail::make_row(setup, f, remainder_mass(g), -g * std::expm1(-g), family.grid));
        } else {
            for (std::size_t j = 0; j < f.size(); ++j) f[j] = lobe_integrand(g, setup.rho[j]);
            family.rows.push_back(detail::make_row(setup, f, -std::expm1(-g), g, family.grid));
        }
    }
    return family;
}

void check_g(double g) {
    if (!(g >= 0.0 && g <= ScatterLobeTable::kMaxG)) fail("lobe parameter g = {} outside [0, {}]", g, ScatterLobeTable::kMaxG);
}

}  // namespace

ScatterLobeTable::ScatterLobeTable(std::shared_ptr<const Data> data)
    : data_(std::move(data)), data_has_first_order_(data_->first_order != nullptr) {
    const detail::RadialFamily& family = *data_->family;
    const std::size_t rows = family.rows.size();
    grid_.log_g_min = kLogGMin;
    grid_.inv_g_step = kInvGStep;
    grid_.g_position_max = (kLogGMax - kLogGMin) * kInvGStep;
    grid_.last_first = kGNodes - 3;
    grid_.log_zeta0 = family.grid.log_x0;
    grid_.inv_zeta_step = 1.0 / family.grid.step;
    grid_.shared_interior_end.assign(rows, 0.0);
    grid_.log_mass.assign(rows, 0.0);
    for (const auto& row : family.rows) grid_.rows.push_back(row.log_value.data());
    for (std::size_t r = 0; r + 3 < rows; ++r) {
        std::size_t n = family.rows[r].log_value.size();
        bool at_zero = true;
        for (std::size_t i = 0; i < 4; ++i) {
            n = std::min(n, family.rows[r + i].log_value.size());
            at_zero = at_zero && family.rows[r + i].lo == 0;
        }
        grid_.shared_interior_end[r] = at_zero ? static_cast<double>(n) - 2.0 : 0.0;
    }
    for (std::size_t r = 1; r < rows; ++r) {
        const double g = node_g(static_cast<int>(r) - 1);
        grid_.log_mass[r] = std::log(data_has_first_order_ ? remainder_mass(g) : -std::expm1(-g));
    }
}

std::shared_ptr<const ScatterLobeTable> ScatterLobeTable::get(std::shared_ptr<const RadialStatistics> stats) {
    const bool first_order_apart = stats->psd_jump_radius() > 0.0;
    const std::string key = fmt::format("{}:{}:g={}..{}x{}", first_order_apart ? "lobe-m2" : "lobe", stats->cache_key(),
                                        kMinG, kMaxG, kNodesPerDecade);
    auto family = detail::cached_family(key, kGNodes + 1, [&] { return build(*stats, first_order_apart); });
    return std::make_shared<const ScatterLobeTable>(std::make_shared<const Data>(
        Data{family, first_order_apart ? std::move(stats) : nullptr,
             fmt::format("{}:v{}", key, detail::kFamilyFormatVersion)}));
}

ScatterLobeTable::Stencil ScatterLobeTable::stencil(double log_g) const {
    const double t = g_position(log_g);
    const int first = stencil_first(t);
    const double u = t - first;
    const std::array<math::Pair, 4> w = detail::cubic_weights(math::Pair{u, u});
    return {first, {w[0][0], w[1][0], w[2][0], w[3][0]}};
}

// Row by row with the rows' own extensions: zeta outside the nodes some row of the stencil shares.
[[gnu::noinline]] double ScatterLobeTable::lobe_log_value_by_rows(double log_g, double log_zeta, bool with_mass) const {
    const Stencil s = stencil(log_g);
    double value = 0.0;
    for (int i = 0; i < 4; ++i) {
        const double mass = with_mass ? grid_.log_mass[s.first + i] : 0.0;
        value += s.w[i] * (data_->family->log_value(s.first + i, log_zeta) + mass);
    }
    return value;
}

// ln s_g (ln S_g with_mass) for ln g in [ln kMinG, ln kMaxG]: the inline bicubic, else row by row.
double ScatterLobeTable::lobe_log_value(double log_g, double log_zeta, bool with_mass) const {
    double value;
    return interior_log_value(log_g, log_zeta, with_mass, value) ? value
                                                                 : lobe_log_value_by_rows(log_g, log_zeta, with_mass);
}

const std::string& ScatterLobeTable::key() const { return data_->key; }

double ScatterLobeTable::rows_shape(double g, double zeta) const {
    const detail::RadialFamily& f = *data_->family;
    if (!(zeta >= 0.0) || std::isinf(zeta)) return 0.0;
    const double log_zeta = zeta > 0.0 ? std::log(zeta) : -1e300;
    if (g < kMinG) {
        // Linear in g between the g -> 0 limit and the first node (error O(g^2)).
        const double s0 = zeta > 0.0 ? std::exp(f.log_value(0, log_zeta)) : f.value(0, 0.0);
        const double s1 = zeta > 0.0 ? std::exp(f.log_value(1, log_zeta)) : f.value(1, 0.0);
        return s0 + (g / kMinG) * (s1 - s0);
    }
    return std::exp(lobe_log_value(std::log(g), log_zeta, false));
}

double ScatterLobeTable::shape(double g, double zeta) const {
    check_g(g);
    if (!data_->first_order) return rows_shape(g, zeta);
    if (g == 0.0) return data_->first_order->psd_unit(zeta);
    return eval(g, zeta) / math::one_minus_exp(g);
}

double ScatterLobeTable::eval(double g, double zeta) const {
    check_g(g);
    if (g == 0.0) return 0.0;
    if (!data_->first_order) return math::one_minus_exp(g) * rows_shape(g, zeta);
    if (!(zeta >= 0.0) || std::isinf(zeta)) return 0.0;
    return g * std::exp(-g) * data_->first_order->psd_unit(zeta) + remainder_mass(g) * rows_shape(g, zeta);
}

double ScatterLobeTable::eval_at_logs(double log_g, double log_zeta) const {
    log_g = std::min(log_g, kLogGMax);
    if (!(log_g >= kLogGMin)) return eval(std::exp(log_g), std::exp(log_zeta));
    const double rows = math::fast_exp(lobe_log_value(log_g, log_zeta, true));
    if (!data_->first_order) return rows;
    const double g = math::fast_exp(log_g);
    return g * math::fast_exp(-g) * data_->first_order->psd_unit(math::fast_exp(log_zeta)) + rows;
}

double ScatterLobeTable::log_eval_outside(double log_g, double log_zeta) const {
    log_g = std::min(log_g, kLogGMax);
    if (data_->first_order || !(log_g >= kLogGMin)) return math::fast_log(eval_at_logs(log_g, log_zeta));
    return lobe_log_value(log_g, log_zeta, true);
}

double ScatterLobeTable::radial_cdf(double g, double zeta) const {
    check_g(g);
    const detail::RadialFamily& f = *data_->family;
    double rows;
    if (g < kMinG) {
        rows = f.cdf(0, zeta) + (g / kMinG) * (f.cdf(1, zeta) - f.cdf(0, zeta));
    } else {
        const Stencil s = stencil(std::log(g));
        rows = 0.0;
        for (int i = 0; i < 4; ++i) rows += s.w[i] * f.cdf(s.first + i, zeta);
    }
    rows = std::clamp(rows, 0.0, 1.0);
    if (!data_->first_order) return rows;
    const double first = data_->first_order->radial_cdf(zeta);
    if (g == 0.0) return first;
    return std::clamp((g * std::exp(-g) * first + remainder_mass(g) * rows) / math::one_minus_exp(g), 0.0, 1.0);
}

double ScatterLobeTable::inverse_radial_cdf(double g, double u) const {
    check_g(g);
    if (!(u > 0.0)) return 0.0;
    u = std::min(u, 1.0 - 1e-16);
    const detail::RadialFamily& f = *data_->family;
    // Bracket from the neighbouring rows' node intervals, then a safeguarded Newton iteration in x = ln zeta on the
    // interpolated CDF (rtsafe): the slope is 2 pi zeta^2 shape(g, zeta), the interpolated density, which equals the
    // interpolated CDF's slope to interpolation accuracy (enough for fast convergence); a step that leaves the
    // bracket or does not halve the previous one bisects instead. 3 to 5 iterations where bisection took 48.
    // The first iterate: the rows' bracket midpoints weighted as the rows are.
    double a = 1e300, b = -1e300, x = 0.0;
    const bool low = g < kMinG;
    const Stencil s = low ? Stencil{0, {1.0 - g / kMinG, g / kMinG, 0.0, 0.0}} : stencil(std::log(g));
    for (int i = 0; i < (low ? 2 : 4); ++i) {
        double lo, hi;
        f.bracket(s.first + i, u, lo, hi);
        a = std::min(a, lo);
        b = std::max(b, hi);
        x += s.w[i] * 0.5 * (lo + hi);
    }
    a -= 0.05;
    b += 0.05;
    for (int it = 0; it < 40 && radial_cdf(g, std::exp(a)) > u; ++it) a -= 1.0;
    for (double step = 1.0; step < 1e3 && radial_cdf(g, std::exp(b)) < u; step *= 2.0) b += step;  // through the tail
    if (!(x > a && x < b)) x = 0.5 * (a + b);
    double step = b - a, previous = step;
    for (int it = 0; it < 100 && b - a > kInverseTolerance; ++it) {
        const double zeta = std::exp(x);
        const double residual = radial_cdf(g, zeta) - u;
        (residual < 0.0 ? a : b) = x;
        const double slope = 2.0 * std::numbers::pi * zeta * zeta * shape(g, zeta);
        const double newton = x - residual / slope;
        if (std::abs(newton - x) < kInverseTolerance) return std::exp(newton);  // converged (also: step below round-off)
        previous = step;
        if (newton > a && newton < b && 2.0 * std::abs(newton - x) <= std::abs(previous)) {
            step = newton - x;
            x = newton;
        } else {
            step = 0.5 * (b - a);
            x = 0.5 * (a + b);
        }
    }
    return std::exp(x);
}

}  // namespace surfscatter::surface
