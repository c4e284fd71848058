#include "surfscatter/surface/radial_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <mutex>


#include "surfscatter/core/table_cache.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::surface::detail {
namespace {

constexpr int kPointsPerDecade = 256;   // FFTLog resolution
constexpr int kStride = 2;              // stored every kStride-th output
constexpr int kEdgeDecades = 2;         // outputs this close to the array ends ring and are discarded
constexpr double kFloor = 1e-11;        // below kFloor * peak the direct transform is replaced (see make_row)

}  // namespace

TransformSetup make_transform_setup(const RadialStatistics& stats, double max_exponent) {
    const double l = stats.correlation_length();
    // r_* where max_exponent (1 - rho) = 1: the narrowest feature of any row; bisection in ln r.
    double lo = std::log(l) - 80.0, hi = std::log(l);
    if (max_exponent * (1.0 - stats.acv_normalized(l)) > 1.0) {
        for (int it = 0; it < 200; ++it) {
            const double mid = 0.5 * (lo + hi);
            (max_exponent * (1.0 - stats.acv_normalized(std::exp(mid))) > 1.0 ? hi : lo) = mid;
        }
    }
    const double log10_r_min = std::min(hi / std::log(10.0), std::log10(l)) - 16.0;
    const double log10_r_max = std::log10(l) + 6.0;
    int n = static_cast<int>(std::ceil((log10_r_max - log10_r_min) * kPointsPerDecade));
    n += n % 2;
    TransformSetup setup;
    setup.hankel = std::make_unique<FftLogHankel>(std::pow(10.0, log10_r_min), std::pow(10.0, log10_r_max), n);
    setup.rho.resize(n);
    setup.base.resize(n);
    for (int j = 0; j < n; ++j) {
        setup.rho[j] = stats.acv_normalized(setup.hankel->r(j));
        setup.base[j] = stats.psd_unit(setup.hankel->zeta(j));
    }
    return setup;
}

LogGrid stored_grid(const TransformSetup& setup) {
    const FftLogHankel& h = *setup.hankel;
    const int first = kEdgeDecades * kPointsPerDecade;
    LogGrid g;
    g.log_x0 = std::log(h.zeta(first));
    g.step = h.log_step() * kStride;
    g.n = (h.size() - 2 * first) / kStride;
    return g;
}

RadialRow make_row(const TransformSetup& setup, const std::vector<double>& f, double mass, double tail_weight,
                   const LogGrid& stored) {
    const FftLogHankel& h = *setup.hankel;
    std::vector<double> p = h.transform(f);
    std::vector<double> remainder_input(f.size());
    for (std::size_t j = 0; j < f.size(); ++j) remainder_input[j] = f[j] - tail_weight * setup.rho[j];
    std::vector<double> q = h.transform(remainder_input);
    const double scale = 1.0 / (2.0 * kPi * mass);
    for (double& v : p) v *= scale;
    for (double& v : q) v *= scale;
    const double c = tail_weight / mass;
    const int first = kEdgeDecades * kPointsPerDecade;
    const int last = first + (stored.n - 1) * kStride;  // inclusive, on the FFTLog grid
    double peak = 0.0, q_max = 0.0;
    for (int j = first; j <= last; ++j) {
        peak = std::max(peak, p[j]);
        q_max = std::max(q_max, std::abs(q[j]));
    }
    int end = last;
    bool in_tail = false;
    for (int j = first; j <= last; ++j) {
        if (!in_tail && p[j] > kFloor * peak) continue;
        in_tail = true;
        const double composed = c * setup.base[j] + q[j];
        if (std::abs(q[j]) < 1e-10 * c * setup.base[j]) {  // remainder negligible: the row is c P-hat from here
            p[j] = c * setup.base[j];
            end = j;
            break;
        }
        if (!(composed > 1e-9 * q_max)) {  // remainder no longer accurate against the value: stop before
            end = j - 1;
            break;
        }
        p[j] = composed;
    }
    end = first + std::max(8, (end - first) / kStride) * kStride;
    end = std::min(end, last);
    RadialRow row;
    row.lo = 0;
    if (in_tail && c > 0.0 && setup.base[end] > 0.0) {
        const int back = std::max(first, end - kPointsPerDecade / 4);
        const double e1 = p[end] / (c * setup.base[end]) - 1.0;
        const double e0 = setup.base[back] > 0.0 ? p[back] / (c * setup.base[back]) - 1.0 : 0.0;
        row.tail_eps = e1;
        if (e0 * e1 > 0.0 && back < end)
            row.tail_kappa = std::clamp(std::log(e1 / e0) / ((end - back) * h.log_step()), -4.0, 0.0);
    }
    // Radial CDF on the fine grid: mass below the first node (flat p), then a 4-point rule in ln zeta
    // (integrand 2 pi zeta^2 p, weights (-1, 13, 13, -1)/24).
    auto integrand = [&](int j) { return 2.0 * kPi * h.zeta(j) * h.zeta(j) * std::max(p[j], 0.0); };
    double cumulative = kPi * h.zeta(first) * h.zeta(first) * p[first];
    const double dy = h.log_step();
    for (int j = first; j <= end; ++j) {
        if ((j - first) % kStride == 0) {
            row.log_value.push_back(std::log(std::max(p[j], std::numeric_limits<double>::min())));
            row.cdf.push_back(cumulative);
        }
        if (j < end) {
            const double f0 = integrand(std::max(j - 1, 0)), f1 = integrand(j), f2 = integrand(j + 1),
                         f3 = integrand(std::min(j + 2, h.size() - 1));
            cumulative += dy * (-f0 + 13.0 * f1 + 13.0 * f2 - f3) / 24.0;
        }
    }
    // Tail slope over the last half decade of the row (clamped below -2 so the tail mass is finite).
    const int k1 = static_cast<int>(row.log_value.size()) - 1;
    const int k0 = std::max(0, k1 - kPointsPerDecade / (2 * kStride));
    const double slope = k1 > k0 ? (row.log_value[k1] - row.log_value[k0]) / ((k1 - k0) * stored.step) : -3.0;
    row.tail_slope = std::min(slope, -2.05);
    // Make the CDF monotone (tiny negative ringing increments) and keep it below 1.
    for (std::size_t k = 1; k < row.cdf.size(); ++k) row.cdf[k] = std::max(row.cdf[k], row.cdf[k - 1]);
    return row;
}

void RadialFamily::set_base(const RadialStatistics& stats) {
    log_base.resize(grid.n);
    log_base_ccdf.resize(grid.n);
    for (int j = 0; j < grid.n; ++j) {
        log_base[j] = std::log(std::max(stats.psd_unit(grid.x(j)), 1e-300));
        log_base_ccdf[j] = std::log(std::max(1.0 - stats.radial_cdf(grid.x(j)), 1e-300));
    }
}

namespace {
constexpr double kUnderflow = -650.0;
constexpr double kLogMaxRadius = 690.0;  // ln of the largest radius inverse_cdf returns (1e300)  // ln P-hat below this: P-hat is numerically gone, use the power law

// Top node of a row and whether the P-hat-shaped tail is usable there.
struct Tail {
    int top;          // stored-grid index of the row's last node
    bool base_shape;  // tail follows P-hat
};
Tail tail_of(const RadialFamily& f, const RadialRow& r) {
    const int top = r.lo + static_cast<int>(r.log_value.size()) - 1;
    return {top, f.log_base[top] > kUnderflow};
}
}  // namespace

double RadialFamily::log_value(int row, double log_zeta) const {
    const RadialRow& r = rows[row];
    const int n = static_cast<int>(r.log_value.size());
    const double t = (log_zeta - grid.log_x0) / grid.step - r.lo;
    if (t <= 0.0) return r.log_value.front();
    if (t < n - 1) return cubic_interpolate(r.log_value.data(), n, t);
    const Tail tail = tail_of(*this, r);
    const double tg = t + r.lo;  // position on the stored grid
    if (tail.base_shape && tg < grid.n - 1) {
        const double base = cubic_interpolate(log_base.data(), grid.n, tg);
        if (base > kUnderflow) {
            const double log_ratio = (tg - tail.top) * grid.step;  // ln(zeta / zeta_top)
            return r.log_value.back() + base - log_base[tail.top] - std::log1p(r.tail_eps) +
                   std::log1p(r.tail_eps * std::exp(r.tail_kappa * log_ratio));
        }
    }
    if (tail.base_shape) {
        // Beyond the stored grid: P-hat continued with the slope of its own last half decade.
        const int k0 = grid.n - 1 - kPointsPerDecade / (2 * kStride);
        const double slope = std::min((log_base[grid.n - 1] - log_base[k0]) / ((grid.n - 1 - k0) * grid.step), -2.05);
        return r.log_value.back() + log_base[grid.n - 1] - log_base[tail.top] + slope * (tg - (grid.n - 1)) * grid.step;
    }
    return r.log_value.back() + r.tail_slope * (t - (n - 1)) * grid.step;
}

double RadialFamily::value(int row, double zeta) const {
    if (!(zeta >= 0.0)) return 0.0;
    if (zeta == 0.0) return std::exp(rows[row].log_value.front());
    if (std::isinf(zeta)) return 0.0;
    return std::exp(log_value(row, std::log(zeta)));
}

namespace {
// Mass of the tail between the row's top node and zeta (zeta beyond the top).
double tail_mass(const RadialFamily& f, const RadialRow& r, double zeta) {
    const Tail tail = tail_of(f, r);
    const double zt = f.grid.x(tail.top);
    const double pt = std::exp(r.log_value.back());
    const double tg = f.grid.position(zeta);
    if (tail.base_shape) {
        // c P-hat (1 + eps (zeta/zt)^kappa), c = p_top / (P-hat(zt)(1 + eps)): the P-hat part from the complementary
        // CDF, the eps part with P-hat's local power law at zt.
        const double base_top = std::exp(f.log_base[tail.top]);
        const double c = pt / (base_top * (1.0 + r.tail_eps));
        const double outside_top = std::exp(f.log_base_ccdf[tail.top]);
        const double outside =
            tg < f.grid.n - 1 ? std::exp(cubic_interpolate(f.log_base_ccdf.data(), f.grid.n, tg)) : 0.0;
        const int k0 = std::max(0, tail.top - 8);
        const double base_slope = (f.log_base[tail.top] - f.log_base[k0]) / ((tail.top - k0) * f.grid.step);
        const double e = base_slope + r.tail_kappa + 2.0;
        const double x = zeta / zt;
        const double eps_part = e < -1e-3 ? r.tail_eps * 2.0 * kPi * base_top * zt * zt * (std::pow(x, e) - 1.0) / e : 0.0;
        return c * (std::max(outside_top - outside, 0.0) + eps_part);
    }
    const double s = r.tail_slope;
    return 2.0 * kPi * pt * zt * zt / (s + 2.0) * (std::pow(zeta / zt, s + 2.0) - 1.0);
}
}  // namespace

double RadialFamily::cdf(int row, double zeta) const {
    const RadialRow& r = rows[row];
    if (!(zeta > 0.0)) return 0.0;
    if (std::isinf(zeta)) return 1.0;
    const int n = static_cast<int>(r.cdf.size());
    const double t = (std::log(zeta) - grid.log_x0) / grid.step - r.lo;
    if (t <= 0.0) return std::min(1.0, kPi * zeta * zeta * std::exp(r.log_value.front()));
    if (t >= n - 1) return std::min(1.0, r.cdf.back() + tail_mass(*this, r, zeta));
    return std::clamp(cubic_interpolate(r.cdf.data(), n, t), 0.0, 1.0);
}

void RadialFamily::bracket(int row, double u, double& lo, double& hi) const {
    const RadialRow& r = rows[row];
    if (u <= r.cdf.front()) {
        lo = hi = std::log(std::max(inverse_cdf(row, u), 1e-300));
        return;
    }
    if (u >= r.cdf.back()) {
        lo = hi = grid.log_x0 + (r.lo + static_cast<int>(r.cdf.size()) - 1) * grid.step;
        return;
    }
    const int k = static_cast<int>(std::upper_bound(r.cdf.begin(), r.cdf.end(), u) - r.cdf.begin()) - 1;
    lo = grid.log_x0 + (r.lo + k) * grid.step;
    hi = lo + grid.step;
}

double RadialFamily::inverse_cdf(int row, double u) const {
    const RadialRow& r = rows[row];
    if (!(u > 0.0)) return 0.0;
    const int n = static_cast<int>(r.cdf.size());
    const double p0 = std::exp(r.log_value.front());
    if (u <= r.cdf.front()) return std::sqrt(u / (kPi * p0));
    double a, b;
    if (u >= r.cdf.back()) {
        // Expand a bracket through the tail (doubling in ln zeta).
        a = grid.log_x0 + (r.lo + n - 1) * grid.step;
        b = a + 1.0;
        for (int it = 0; it < 60 && b < kLogMaxRadius && cdf(row, std::exp(b)) < u; ++it)
            b = std::min(b + (b - a), kLogMaxRadius);
        if (cdf(row, std::exp(b)) < u) return std::exp(b);  // u beyond the tabulated mass (round-off): largest radius
    } else {
        const int k = static_cast<int>(std::upper_bound(r.cdf.begin(), r.cdf.end(), u) - r.cdf.begin()) - 1;
        a = grid.log_x0 + (r.lo + k) * grid.step;
        b = a + grid.step;
    }
    // Bisection on the interpolated CDF (monotone to interpolation accuracy).
    for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (a + b);
        (cdf(row, std::exp(mid)) < u ? a : b) = mid;
    }
    return std::exp(0.5 * (a + b));
}

std::shared_ptr<const RadialFamily> cached_family(const std::string& key, std::size_t rows,
                                                  const std::function<RadialFamily()>& build) {
    static std::mutex mutex;
    static std::map<std::string, std::weak_ptr<const RadialFamily>> families;
    std::lock_guard lock(mutex);
    if (auto existing = families[key].lock()) return existing;
    auto family = std::make_shared<RadialFamily>();
    std::vector<double> extra;
    if (!load_family(key, *family, extra) || family->rows.size() != rows) {
        *family = build();
        save_family(key, *family, {});
    }
    families[key] = family;
    return family;
}

std::filesystem::path cache_file(const std::string& key) { return table_cache_file("radial-table", kFamilyFormatVersion, key); }

void save_family(const std::string& key, const RadialFamily& family, const std::vector<double>& extra) {
    std::vector<double> payload = {family.grid.log_x0, family.grid.step, static_cast<double>(family.grid.n),
                                   static_cast<double>(family.rows.size()), static_cast<double>(extra.size())};
    payload.insert(payload.end(), extra.begin(), extra.end());
    payload.insert(payload.end(), family.log_base.begin(), family.log_base.end());
    payload.insert(payload.end(), family.log_base_ccdf.begin(), family.log_base_ccdf.end());
    for (const RadialRow& r : family.rows) {
        payload.push_back(r.lo);
        payload.push_back(static_cast<double>(r.log_value.size()));
        payload.push_back(r.tail_slope);
        payload.push_back(r.tail_eps);
        payload.push_back(r.tail_kappa);
        payload.insert(payload.end(), r.log_value.begin(), r.log_value.end());
        payload.insert(payload.end(), r.cdf.begin(), r.cdf.end());
    }
    save_cached_table(cache_file(key), kFamilyFormatVersion, key, payload);
}

bool load_family(const std::string& key, RadialFamily& family, std::vector<double>& extra) {
    try {
        const std::optional<std::vector<double>> loaded = load_cached_table(cache_file(key), kFamilyFormatVersion, key);
        if (!loaded || loaded->size() < 5) return false;
        const std::vector<double>& payload = *loaded;
        std::size_t pos = 0;
        auto next = [&]() { return pos < payload.size() ? payload[pos++] : std::numeric_limits<double>::quiet_NaN(); };
        RadialFamily f;
        f.grid.log_x0 = next();
        f.grid.step = next();
        f.grid.n = static_cast<int>(next());
        const double rows = next(), extras = next();
        if (!(rows >= 1 && rows < 1e7 && extras >= 0 && extras < 1e7 && f.grid.step > 0)) return false;
        extra.assign(static_cast<std::size_t>(extras), 0.0);
        for (double& e : extra) e = next();
        if (!(f.grid.n >= 8 && pos + 2 * static_cast<std::size_t>(f.grid.n) <= payload.size())) return false;
        f.log_base.assign(payload.begin() + pos, payload.begin() + pos + f.grid.n);
        pos += f.grid.n;
        f.log_base_ccdf.assign(payload.begin() + pos, payload.begin() + pos + f.grid.n);
        pos += f.grid.n;
        f.rows.resize(static_cast<std::size_t>(rows));
        for (RadialRow& r : f.rows) {
            r.lo = static_cast<int>(next());
            const double n = next();
            r.tail_slope = next();
            r.tail_eps = next();
            r.tail_kappa = next();
            if (!(r.tail_eps > -1.0)) return false;
            if (!(n >= 4 && r.lo >= 0 && r.lo + n <= f.grid.n && pos + 2 * static_cast<std::size_t>(n) <= payload.size())) return false;
            r.log_value.assign(payload.begin() + pos, payload.begin() + pos + static_cast<std::size_t>(n));
            pos += static_cast<std::size_t>(n);
            r.cdf.assign(payload.begin() + pos, payload.begin() + pos + static_cast<std::size_t>(n));
            pos += static_cast<std::size_t>(n);
        }
        if (pos != payload.size()) return false;
        family = std::move(f);
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace surfscatter::surface::detail
