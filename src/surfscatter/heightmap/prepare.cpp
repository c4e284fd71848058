#include "surfscatter/heightmap/prepare.hpp"

#include <algorithm>
#include <cstddef>
#include <exception>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::heightmap {

double wrap_jump_ratio(const HeightMap& map) {
    const std::size_t nx = map.nx(), ny = map.ny();
    double ratio = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        const std::size_t n = axis == 0 ? nx : ny, m = axis == 0 ? ny : nx;
        auto h = [&](std::size_t i, std::size_t j) { return axis == 0 ? map(i, j) : map(j, i); };
        double jump = 0.0, step = 0.0;
        for (std::size_t j = 0; j < m; ++j) {
            const double d = h(0, j) - h(n - 1, j);
            jump += d * d;
            for (std::size_t i = 0; i + 1 < n; ++i) {
                const double s = h(i + 1, j) - h(i, j);
                step += s * s;
            }
        }
        jump /= static_cast<double>(m);
        step /= static_cast<double>(m) * static_cast<double>(n - 1);
        ratio = std::max(ratio, step > 0.0 ? jump / step : (jump > 0.0 ? HUGE_VAL : 1.0));
    }
    return ratio;
}

bool is_periodic(const HeightMap& map) {
    if (map.source.periodic) return *map.source.periodic;
    return !map.has_invalid() && wrap_jump_ratio(map) <= kPeriodicJumpRatio;
}

namespace {

// A nesting index as typed: a finite number of um > 0, or "none" (0).
double parse_nesting_index(const std::string& text, const std::string& where) {
    if (text == "none") return 0.0;
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size() || !std::isfinite(value) || !(value > 0.0))
        fail("{} must be a nesting index in um (> 0) or none, got '{}'", where, text);
    return value;
}

double rms_of(const HeightMap& map) { return height_moments(map).rms; }

}  // namespace

std::optional<double> parse_lambda_c(const std::string& text, const std::string& where) {
    if (text == "auto") return std::nullopt;
    return parse_nesting_index(text, where);
}

double parse_lambda_s(const std::string& text, const std::string& where) { return parse_nesting_index(text, where); }

PreparedMap prepare(const HeightMap& read, const Preparation& how) {
    PreparedMap p{read, how, {}, {}, false, {}, std::nullopt, height_moments(read).rms, 0, 0, 0};
    const bool periodic = is_periodic(read);
    HeightMap map = apply_outlier_policy(read, how.outliers, p.outliers);
    map = align_rows(map, how.rows, p.rows);
    p.rows_aligned = how.rows == RowAlignment::median || (how.rows == RowAlignment::automatic && p.rows.detected);
    // The form is a least-squares projection: its rms and the residual's add in quadrature.
    const double before_form = rms_of(map);
    map = remove_form(map, how.form);
    const double after_form = rms_of(map);
    p.form_rms_um = std::sqrt(std::max(0.0, before_form * before_form - after_form * after_form));
    if (how.lambda_s_um > 0) {
        Filtered s = s_filter(map, how.lambda_s_um);
        p.short_rms_um = rms_of(s.removed);
        map = std::move(s.kept);
    }
    const double lambda_c = how.lambda_c_um ? *how.lambda_c_um : default_lambda_c(map, &p.lambda_c_reason, kShortestWavinessUm);
    p.applied.lambda_c_um = lambda_c;
    if (lambda_c > 0) {
        if (how.lambda_s_um > 0 && !(lambda_c > how.lambda_s_um))
            fail("lambda_c ({} um) must be longer than lambda_s ({} um): the band between them is the roughness",
                 lambda_c, how.lambda_s_um);
        Filtered l = l_filter(map, lambda_c);
        p.waviness_rms_um = rms_of(l.removed);
        p.waviness = std::move(l.removed);
        map = std::move(l.kept);
    }
    // A periodic map stays periodic through the outliers and the form (judged as read: a form fitted to it is noise
    // that breaks the wrap-around), not through row alignment or the filters' edges.
    map.source.periodic = periodic && !p.rows_aligned && how.lambda_s_um == 0 && lambda_c == 0;
    p.map = std::move(map);
    return p;
}

std::string describe(const PreparedMap& p) {
    std::string text = fmt::format("prepared: outliers {} ({} points); {}; form {} (removed rms {:.4g} um)",
                                   to_string(p.applied.outliers), p.outliers.count,
                                   describe(p.rows, p.applied.rows), to_string(p.applied.form), p.form_rms_um);
    text += p.applied.lambda_s_um > 0
                ? fmt::format("; S-filter lambda_s {:.4g} um (removed rms {:.4g} um)", p.applied.lambda_s_um, p.short_rms_um)
                : "; no S-filter";
    const double lambda_c = p.applied.lambda_c_um.value_or(0.0);
    text += lambda_c > 0 ? fmt::format("; L-filter lambda_c {:.4g} um: waviness rms {:.4g} um", lambda_c, p.waviness_rms_um)
                         : "; no L-filter";
    if (!p.lambda_c_reason.empty()) text += " (" + p.lambda_c_reason + ")";
    text += fmt::format("; rms {:.4g} um (as read {:.4g} um)", rms_of(p.map), p.read_rms_um);
    return text;
}

}  // namespace surfscatter::heightmap
