#include "surfscatter/heightmap/rows.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr std::size_t kMinTestRows = 8;
constexpr double kMaxRatio = 1e12;
// The median of chi^2_1 (a DCT bin of white noise over its mean), and the relative standard deviation of the median
// of K such bins times sqrt(K): sqrt(1/4 / f(q)^2) / q, f the chi^2_1 density at its median q.
constexpr double kChiSquare1Median = 0.454936;
constexpr double kMedianSpread = 2.33;  // R when the rows have no roughness of their own and their means still differ

// Least-squares polynomial of degree `degree` in y through values[i] at rows[i]; the fitted values at those rows.
std::vector<double> polynomial_fit(const std::vector<double>& rows, const std::vector<double>& values, int degree,
                                   double ny) {
    const std::size_t m = rows.size();
    const int terms = std::min<int>(degree + 1, static_cast<int>(m));
    Eigen::MatrixXd a(m, terms);
    Eigen::VectorXd b(m);
    for (std::size_t i = 0; i < m; ++i) {
        const double t = ny > 1 ? 2.0 * rows[i] / (ny - 1.0) - 1.0 : 0.0;  // [-1, 1]: well conditioned
        double p = 1.0;
        for (int k = 0; k < terms; ++k, p *= t) a(static_cast<Eigen::Index>(i), k) = p;
        b(static_cast<Eigen::Index>(i)) = values[i];
    }
    const Eigen::VectorXd c = a.colPivHouseholderQr().solve(b);
    const Eigen::VectorXd fit = a * c;
    return std::vector<double>(fit.data(), fit.data() + m);
}

double median(std::vector<double>& v) {
    const std::size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
    const double upper = v[mid];
    if (v.size() % 2) return upper;
    return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid)));
}

// chi^2_nu / nu exceeded with probability kRowOffsetFalseAlarm (Wilson-Hilferty: within 1 % of the exact quantile
// for nu >= 3, conservative below).
double chi_square_quantile_ratio(double nu) {
    const double z = kRowOffsetFalseAlarmZ, v = 2.0 / (9.0 * nu), c = 1.0 - v + z * std::sqrt(v);
    return c * c * c;
}

// The significance ratio R of rows.hpp from the rows directly linked to the row above; returns the mean variance
// of a row's mean step that the rows' own roughness gives (0 when not tested).
double significance(const HeightMap& map, const std::vector<std::size_t>& link, RowOffsets& found) {
    const std::size_t nx = map.nx(), ny = map.ny();
    std::vector<double> w(map.size(), 0.0);   // D minus its row mean, on the rows tested
    std::vector<std::uint8_t> in(map.size(), 0);
    std::vector<double> rows, means, counts;
    double sum_w2 = 0, dof = 0;
    for (std::size_t iy = 1; iy < ny; ++iy) {
        if (link[iy] != iy - 1) continue;
        double sum = 0;
        std::size_t n = 0;
        for (std::size_t ix = 0; ix < nx; ++ix)
            if (map.valid(ix, iy) && map.valid(ix, iy - 1)) {
                w[iy * nx + ix] = map(ix, iy) - map(ix, iy - 1);
                in[iy * nx + ix] = 1;
                sum += w[iy * nx + ix];
                ++n;
            }
        const double mean = sum / static_cast<double>(n);
        for (std::size_t ix = 0; ix < nx; ++ix)
            if (in[iy * nx + ix]) {
                w[iy * nx + ix] -= mean;
                sum_w2 += w[iy * nx + ix] * w[iy * nx + ix];
            }
        dof += static_cast<double>(n - 1);
        rows.push_back(static_cast<double>(iy));
        means.push_back(mean);
        counts.push_back(static_cast<double>(n));
    }
    const std::size_t m = rows.size();
    if (m < kMinTestRows) {
        found.reason = fmt::format("{} pairs of neighbouring rows share {} valid points, fewer than the {} the test of "
                                   "row offsets needs: not tested", m, kMinRowOverlap, kMinTestRows);
        return 0.0;
    }
    const double s2 = sum_w2 / dof;
    // Integrated autocorrelation of D along x, up to its first non-positive lag.
    double tau = 1.0;
    if (s2 > 0)
        for (std::size_t k = 1; k < nx / 2; ++k) {
            double c = 0;
            std::size_t pairs = 0;
            for (std::size_t iy = 1; iy < ny; ++iy)
                for (std::size_t ix = 0; ix + k < nx; ++ix)
                    if (in[iy * nx + ix] && in[iy * nx + ix + k]) {
                        c += w[iy * nx + ix] * w[iy * nx + ix + k];
                        ++pairs;
                    }
            const double rho = pairs ? c / static_cast<double>(pairs) / s2 : 0.0;
            if (!(rho > 0)) break;
            tau += 2.0 * rho;
        }
    const std::vector<double> form = polynomial_fit(rows, means, 2, static_cast<double>(ny));
    std::vector<double> residual(m);
    double scatter = 0, expected = 0;
    for (std::size_t i = 0; i < m; ++i) {
        residual[i] = means[i] - form[i];
        scatter += residual[i] * residual[i];
        expected += s2 * tau / counts[i];
    }
    // Independent rows: a smooth surface's row means follow each other over its correlation length (positive
    // lags), white offsets' steps alternate (rho_1 = -1/2): nu = m / (1 + 2 sum of the leading positive rho_k).
    double sum_rho = 0;
    for (std::size_t k = 1; k < m / 2; ++k) {
        double c = 0;
        for (std::size_t i = 0; i + k < m; ++i) c += residual[i] * residual[i + k];
        const double rho = scatter > 0 ? c / scatter : 0.0;
        if (!(rho > 0)) break;
        sum_rho += rho;
    }
    found.independent_rows = std::max(1.0, static_cast<double>(m - 3) / (1.0 + 2.0 * sum_rho));
    found.threshold = std::max(kRowOffsetRatio, chi_square_quantile_ratio(found.independent_rows));
    scatter *= static_cast<double>(m) / static_cast<double>(m - 3);  // 3 parameters of the quadratic
    found.ratio = expected > 0 ? std::min(scatter / expected, kMaxRatio) : (scatter > 0 ? kMaxRatio : 0.0);
    found.reason = fmt::format(
        "rows' mean steps scatter {:.3g} x what the rows' own roughness gives (R over {} pairs of rows, {:.3g} "
        "independent, tau {:.3g}; offsets when R > {:.3g})", found.ratio, m, found.independent_rows, tau,
        found.threshold);
    return expected / static_cast<double>(m);
}

// W of rows.hpp and the levels' white part. The levels' DCT-II X_k (the even extension: no jump at the ends to leak
// into high frequencies), periodogram P_k = 2 X_k^2 / m (a white series of variance s^2 gives E P_k = s^2 for k >= 1);
// the floor F = the median P_k over k >= 0.7 m (periods 2 - 2.9 rows) over chi^2_1's median (a lay's harmonics are
// lines there, which the median passes over). Without offsets a row level's noise is at most white
// with half a step's variance (rows uncorrelated along y), so W = F / (step_variance / 2). The white part: X_k times
// the Wiener gain min(1, F / S_k), S_k the mean P over k +- 3, taken as 1 where S_k <= 2 F (white within the
// scatter of 7 bins), then the inverse DCT.
std::vector<double> white_part(const std::vector<double>& levels, double step_variance, RowOffsets& found) {
    const std::size_t m = levels.size();
    if (m < kMinTestRows || !(step_variance >= 0)) return levels;
    std::vector<double> c(4 * m);  // cos(pi j / (2 m)): the transform's angles pi k (2 n + 1) / (2 m), mod 4 m
    for (std::size_t j = 0; j < c.size(); ++j) c[j] = std::cos(std::numbers::pi * double(j) / double(2 * m));
    std::vector<double> x(m, 0.0), p(m, 0.0);
    for (std::size_t k = 0; k < m; ++k) {
        for (std::size_t n = 0; n < m; ++n) x[k] += levels[n] * c[(k * (2 * n + 1)) % (4 * m)];
        p[k] = 2.0 * x[k] * x[k] / double(m);
    }
    const std::size_t k0 = static_cast<std::size_t>(std::ceil(0.7 * double(m)));
    std::vector<double> band(p.begin() + static_cast<std::ptrdiff_t>(k0), p.end());
    const double floor = median(band) / kChiSquare1Median, bins = double(m - k0);
    const double null = 0.5 * step_variance;
    found.white_ratio = null > 0 ? std::min(floor / null, kMaxRatio) : (floor > 0 ? kMaxRatio : 0.0);
    found.white_threshold = std::max(kWhiteFloorRatio, 1.0 + kRowOffsetFalseAlarmZ * kMedianSpread / std::sqrt(bins));
    std::vector<double> gained(m);
    for (std::size_t k = 0; k < m; ++k) {
        const std::size_t lo = k >= 3 ? k - 3 : 0, hi = std::min(m - 1, k + 3);
        double smooth = 0;
        for (std::size_t j = lo; j <= hi; ++j) smooth += p[j];
        smooth /= double(hi - lo + 1);
        gained[k] = k == 0 || smooth <= 2.0 * floor ? x[k] : x[k] * floor / smooth;
    }
    std::vector<double> white(m);
    double sum2 = 0;
    for (std::size_t n = 0; n < m; ++n) {
        double v = gained[0];
        for (std::size_t k = 1; k < m; ++k) v += 2.0 * gained[k] * c[(k * (2 * n + 1)) % (4 * m)];
        white[n] = v / double(m);
        sum2 += white[n] * white[n];
    }
    found.white_rms_um = std::sqrt(sum2 / double(m));
    return white;
}

}  // namespace

RowAlignment parse_row_alignment(const std::string& name, const std::string& where) {
    if (name == "none") return RowAlignment::none;
    if (name == "median") return RowAlignment::median;
    if (name == "auto") return RowAlignment::automatic;
    fail("{} must be one of none | median | auto, got '{}'", where, name);
}

std::string to_string(RowAlignment a) {
    switch (a) {
        case RowAlignment::none: return "none";
        case RowAlignment::median: return "median";
        case RowAlignment::automatic: return "auto";
    }
    return "none";
}

RowOffsets find_row_offsets(const HeightMap& map) {
    const std::size_t nx = map.nx(), ny = map.ny();
    RowOffsets found;
    found.offset_um.assign(ny, 0.0);
    std::vector<std::size_t> valid_in_row(ny, 0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) valid_in_row[iy] += map.valid(ix, iy) ? 1 : 0;

    // Levels: running sums of the median steps to the nearest linked row above (link = ny: none).
    std::vector<std::size_t> link(ny, ny);
    std::vector<double> level(ny, 0.0), rows, levels;
    std::vector<double> d;
    d.reserve(nx);
    bool first = true;
    for (std::size_t iy = 0; iy < ny; ++iy) {
        if (valid_in_row[iy] == 0) continue;
        for (std::size_t j = iy; j-- > 0 && !first;) {
            if (valid_in_row[j] < kMinRowOverlap) continue;
            d.clear();
            for (std::size_t ix = 0; ix < nx; ++ix)
                if (map.valid(ix, iy) && map.valid(ix, j)) d.push_back(map(ix, iy) - map(ix, j));
            if (d.size() < kMinRowOverlap) continue;
            link[iy] = j;
            level[iy] = level[j] + median(d);
            break;
        }
        if (link[iy] == ny && !first) ++found.unlinked_rows;
        first = false;
        rows.push_back(static_cast<double>(iy));
        levels.push_back(level[iy]);
    }
    // Minus their cubic in y: tilt and curvature across the rows are form, left for form removal.
    const std::vector<double> form = polynomial_fit(rows, levels, 3, static_cast<double>(ny));
    double sum2 = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const double o = levels[i] - form[i];
        found.offset_um[static_cast<std::size_t>(rows[i])] = o;
        sum2 += o * o;
    }
    found.rms_um = std::sqrt(sum2 / static_cast<double>(rows.size()));
    const double step_variance = significance(map, link, found);
    std::vector<double> detrended(rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i) detrended[i] = found.offset_um[static_cast<std::size_t>(rows[i])];
    const std::vector<double> white_levels = white_part(detrended, step_variance, found);
    found.white_um.assign(ny, 0.0);
    for (std::size_t i = 0; i < rows.size(); ++i) found.white_um[static_cast<std::size_t>(rows[i])] = white_levels[i];
    const bool steps = found.ratio > found.threshold, white = found.white_ratio > found.white_threshold;
    found.detected = steps && white;
    found.lay = steps && !white;
    if (found.white_threshold > 0)
        found.reason += fmt::format("; white floor across the rows W = {:.3g} x the rows' own (periods 2-2.9 rows; "
                                    "offsets when W > {:.3g}){}", found.white_ratio, found.white_threshold,
                                    found.lay ? ": a profile across the rows (a lay along them), not offsets" : "");
    if (found.unlinked_rows)
        found.reason += fmt::format("; {} rows share fewer than {} valid points with every row above and keep their "
                                    "own level", found.unlinked_rows, kMinRowOverlap);
    return found;
}

HeightMap align_rows(const HeightMap& map, RowAlignment how, RowOffsets& found) {
    if (how == RowAlignment::none) {
        found = RowOffsets{};
        found.reason = "none";
        return map;
    }
    found = find_row_offsets(map);
    if (how == RowAlignment::automatic && !found.detected) return map;
    const std::vector<double>& offsets = how == RowAlignment::automatic ? found.white_um : found.offset_um;
    std::vector<double> h = map.heights();
    for (std::size_t iy = 0; iy < map.ny(); ++iy)
        for (std::size_t ix = 0; ix < map.nx(); ++ix) h[iy * map.nx() + ix] -= offsets[iy];
    return map.with_heights(std::move(h));
}

std::string describe(const RowOffsets& found, RowAlignment how) {
    if (how == RowAlignment::none) return "row alignment: none";
    if (how == RowAlignment::median)
        return fmt::format("row alignment median: offsets rms {:.4g} um, aligned: {}", found.rms_um, found.reason);
    return fmt::format("row alignment auto: row levels rms {:.4g} um, their white part {:.4g} um, {}: {}",
                       found.rms_um, found.white_rms_um,
                       found.detected ? "aligned (their white part removed)"
                                      : (found.lay ? "a lay along the rows, left" : "not significant, left"),
                       found.reason);
}

}  // namespace surfscatter::heightmap
