#include "surfscatter/validity/validity.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::validity {

namespace {

double median(std::vector<double> values) {
    const std::size_t n = values.size();
    std::sort(values.begin(), values.end());
    return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

double trapezoid(const std::vector<double>& x, const std::vector<double>& y) {
    double sum = 0;
    for (std::size_t j = 1; j < x.size(); ++j) sum += 0.5 * (y[j] + y[j - 1]) * (x[j] - x[j - 1]);
    return sum;
}

std::string percent(double fraction) { return fmt::format("{:.3g} %", 100 * fraction); }

}  // namespace

std::string to_string(bsdf::ProfilePolarisation polarisation) {
    return polarisation == bsdf::ProfilePolarisation::s ? "s" : "p";
}

CurveComparison compare_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                               const std::vector<double>& reference_stderr, const std::vector<double>& model,
                               const Criteria& criteria, const std::vector<char>& left_out) {
    if (reference.size() != theta_o_rad.size() || reference_stderr.size() != theta_o_rad.size() ||
        model.size() != theta_o_rad.size() || (!left_out.empty() && left_out.size() != theta_o_rad.size()))
        fail("compare_curves: grid of {} directions, reference {}, its standard errors {}, model {}, flags {}",
             theta_o_rad.size(), reference.size(), reference_stderr.size(), model.size(), left_out.size());
    const double peak = reference.empty() ? 0.0 : *std::max_element(reference.begin(), reference.end());
    CurveComparison c;
    std::vector<double> errors, stderrs;
    for (std::size_t j = 0; j < reference.size(); ++j) {
        if (!(peak > 0) || reference[j] < criteria.peak_fraction * peak || (!left_out.empty() && left_out[j])) continue;
        if (reference_stderr[j] > criteria.max_reference_stderr * reference[j]) {
            ++c.directions_excluded;
            continue;
        }
        const double error = std::abs(model[j] - reference[j]) / reference[j];
        if (errors.empty() || error > c.worst_rel_error) {
            c.worst_rel_error = error;
            c.worst_theta_o_rad = theta_o_rad[j];
        }
        errors.push_back(error);
        c.used.push_back(j);
        stderrs.push_back(reference_stderr[j] / reference[j]);
        c.rel_deviation.push_back(model[j] / reference[j] - 1.0);
    }
    c.directions_used = errors.size();
    if (!errors.empty()) {
        c.median_rel_error = median(errors);
        c.reference_median_rel_stderr = median(stderrs);
    }
    c.reference_rel_stderr = std::move(stderrs);
    return c;
}

BinnedCurves bin_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                        const std::vector<double>& reference_stderr, const std::vector<std::vector<double>>& models,
                        double bin_rad, double k_per_um, double beam_width_um) {
    const std::size_t n = theta_o_rad.size();
    if (reference.size() != n || reference_stderr.size() != n)
        fail("bin_curves: grid of {} directions, reference {}, its standard errors {}", n, reference.size(),
             reference_stderr.size());
    for (const auto& model : models)
        if (model.size() != n) fail("bin_curves: grid of {} directions, a model of {}", n, model.size());
    if (!(bin_rad >= 0) || !std::isfinite(bin_rad)) fail("bin_curves: bin width must be >= 0, got {} rad", bin_rad);
    BinnedCurves out;
    out.models.resize(models.size());
    // Bins of bin_rad from -90 deg, the last one taking the remainder; bin_rad = 0: every direction its own bin.
    const long bins = bin_rad > 0 ? std::max(1L, static_cast<long>(std::floor(kPi / bin_rad))) : 0;
    const auto bin_of = [&](std::size_t j) {
        return bins > 0 ? std::min(bins - 1, static_cast<long>(std::floor((theta_o_rad[j] + kPi / 2) / bin_rad)))
                        : static_cast<long>(j);
    };
    std::size_t j = 0;
    while (j < n) {
        const long b = bin_of(j);
        std::size_t end = j;
        double theta = 0, ref = 0, var = 0;
        std::vector<double> sums(models.size(), 0.0);
        while (end < n && bin_of(end) == b) {
            theta += theta_o_rad[end];
            ref += reference[end];
            var += reference_stderr[end] * reference_stderr[end];
            for (std::size_t m = 0; m < models.size(); ++m) sums[m] += models[m][end];
            ++end;
        }
        const double count = static_cast<double>(end - j);
        const double centre = theta / count;
        const double speckle = 2.0 / (k_per_um * beam_width_um * std::max(std::cos(centre), 1e-3));
        const double independent = std::max(1.0, bin_rad / speckle);
        out.first_direction.push_back(j);
        out.theta_o_rad.push_back(centre);
        out.reference.push_back(ref / count);
        out.reference_stderr.push_back(std::sqrt(var / count / independent));
        for (std::size_t m = 0; m < models.size(); ++m) out.models[m].push_back(sums[m] / count);
        j = end;
    }
    return out;
}

namespace {

// The median over the directions used of the largest change of f(d_j, delta) from f(d_j, 0) for a reference
// moved by delta = +-eps_j of its value, d_j = model / reference - 1 (header).
template <typename F>
double median_over_used(const CurveComparison& c, F&& f) {
    if (c.reference_rel_stderr.empty()) return 0.0;
    std::vector<double> values(c.reference_rel_stderr.size());
    for (std::size_t j = 0; j < values.size(); ++j) {
        const double eps = c.reference_rel_stderr[j], now = f(j, 0.0);
        values[j] = std::max(std::abs(f(j, eps) - now), std::abs(f(j, -eps) - now));
    }
    return median(std::move(values));
}

// |model / reference - 1| once the reference is moved by the fraction delta of its value.
double moved_error(double deviation, double delta) { return std::abs((1.0 + deviation) / (1.0 + delta) - 1.0); }

std::string points(double fraction) { return fmt::format("{:.3g}", 100 * fraction); }

}  // namespace

double error_uncertainty(const ModelResult& m) {
    const CurveComparison& c = m.comparison;
    const double reference =
        median_over_used(c, [&](std::size_t j, double delta) { return moved_error(c.rel_deviation[j], delta); });
    return std::hypot(reference, m.own_rel_uncertainty);
}

double lead_uncertainty(const ModelResult& a, const ModelResult& b) {
    const CurveComparison &ca = a.comparison, &cb = b.comparison;
    if (ca.rel_deviation.size() != cb.rel_deviation.size() || ca.reference_rel_stderr != cb.reference_rel_stderr)
        fail("lead_uncertainty: {} and {} were not compared at the same directions", a.model, b.model);
    const double reference = median_over_used(ca, [&](std::size_t j, double delta) {
        return moved_error(cb.rel_deviation[j], delta) - moved_error(ca.rel_deviation[j], delta);
    });
    return std::sqrt(reference * reference + a.own_rel_uncertainty * a.own_rel_uncertainty +
                     b.own_rel_uncertainty * b.own_rel_uncertainty);
}

Verdict decide(const std::vector<ModelResult>& models, const Criteria& criteria, const std::string& problem,
               const reference::OptionNames& names) {
    const std::string remedy = names.realizations.empty()
                                   ? fmt::format("use a wider {} or measure a larger area", names.bin_deg)
                                   : fmt::format("use more {} or a wider {}", names.realizations, names.bin_deg);
    Verdict v;
    if (models.empty()) fail("decide: no models to compare");
    const CurveComparison& c = models.front().comparison;  // the same reference directions for every model
    std::vector<const ModelResult*> order;
    for (const ModelResult& m : models) order.push_back(&m);
    std::stable_sort(order.begin(), order.end(), [](const ModelResult* a, const ModelResult* b) {
        return a->comparison.median_rel_error < b->comparison.median_rel_error;
    });
    if (!problem.empty())
        v.reference_problem = problem;
    else if (c.directions_used == 0)
        v.reference_problem = fmt::format("no direction has a reference with a standard error within {} of its value "
                                          "({} excluded): {}",
                                          percent(criteria.max_reference_stderr), c.directions_excluded, remedy);
    else if (c.reference_median_rel_stderr > criteria.tolerance)
        v.reference_problem = fmt::format("the reference's median standard error {} exceeds the tolerance {}: {}",
                                          percent(c.reference_median_rel_stderr), percent(criteria.tolerance), remedy);
    if (!v.reference_problem.empty()) {
        v.text = "nothing can be concluded and no model is ruled out: the reference is outside its validity (" +
                 v.reference_problem + ")";
        if (c.directions_used > 0)
            v.text += fmt::format("; against it, for information only, the closest is {} ({})", order.front()->model,
                                  percent(order.front()->comparison.median_rel_error));
        return v;
    }
    v.conclusive = true;
    const ModelResult& best = *order.front();
    v.best_model = best.model;
    v.indistinguishable.push_back(best.model);
    double lead = 0, lead_u = 0;
    std::string runner_up;
    const double useful = kUsefulLead * criteria.tolerance;
    for (std::size_t i = 1; i < order.size(); ++i) {
        const double u = lead_uncertainty(best, *order[i]);
        const double d = order[i]->comparison.median_rel_error - best.comparison.median_rel_error;
        if (d <= std::max(u, useful)) v.indistinguishable.push_back(order[i]->model);
        if (i == 1) lead = d, lead_u = u, runner_up = order[i]->model;
    }
    std::string ruled_out;
    for (const ModelResult* m : order) {
        const double e = m->comparison.median_rel_error;
        if (e <= criteria.tolerance) v.within_tolerance.push_back(m->model);
        const double u = error_uncertainty(*m);
        if (e > criteria.tolerance + 2 * u) {
            v.ruled_out.push_back(m->model);
            ruled_out += fmt::format(" {} ({} +- {})", m->model, percent(e), percent(u));
        }
    }
    if (!ruled_out.empty()) ruled_out = "; ruled out:" + ruled_out;
    const bool best_within = best.comparison.median_rel_error <= criteria.tolerance;
    v.trusted = best_within && v.indistinguishable.size() == 1;
    const std::string best_text = fmt::format("{} (median error {} +- {}, worst {})", best.model,
                                              percent(best.comparison.median_rel_error), percent(error_uncertainty(best)),
                                              percent(best.comparison.worst_rel_error));
    std::string tied;
    for (std::size_t i = 1; i < v.indistinguishable.size(); ++i) {
        const auto it = std::find_if(order.begin(), order.end(),
                                     [&](const ModelResult* m) { return m->model == v.indistinguishable[i]; });
        tied += fmt::format("{}{} ({})", i > 1 ? ", " : "", (*it)->model, percent((*it)->comparison.median_rel_error));
    }
    if (v.trusted) {
        v.text = "trust " + best_text;
        if (!runner_up.empty())
            v.text += fmt::format(": {} points ahead of {}, beyond their uncertainty of {} and a tenth of the "
                                  "tolerance", points(lead), runner_up, points(lead_u));
    } else if (best_within) {
        v.text = fmt::format("no single model can be trusted: {} and {} are indistinguishable at this reference's "
                             "uncertainty (lead over {} {} points, uncertainty {}, a useful lead at least {}); within "
                             "the tolerance {}:",
                             best_text, tied, runner_up, points(lead), points(lead_u), points(useful),
                             percent(criteria.tolerance));
        for (const std::string& name : v.within_tolerance) v.text += " " + name;
    } else {
        v.text = fmt::format("no model is within the tolerance {}: the closest is {}", percent(criteria.tolerance),
                             best_text);
        if (!tied.empty()) v.text += ", indistinguishable from " + tied;
    }
    v.text += ruled_out;
    return v;
}

std::vector<TableRow> table(const std::vector<ProfileCase>& cases) {
    std::vector<TableRow> rows;
    for (const ProfileCase& c : cases)
        for (const ModelResult& m : c.models)
            rows.push_back({m.model, c.wavelength_nm, c.theta_i_deg, to_string(c.polarisation), m.comparison,
                            m.model_energy, c.reference_energy, c.verdict.trusted && c.verdict.best_model == m.model,
                            c.verdict.text});
    return rows;
}

namespace {

// Gauss-Hermite rule for the weight exp(-x^2 / 2) (Golub-Welsch: the eigenvalues of the probabilists' Hermite
// recurrence's Jacobi matrix; weights the squared first components), weights summing to 1.
void gauss_hermite(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
    for (int j = 1; j < n; ++j) jacobi(j, j - 1) = jacobi(j - 1, j) = std::sqrt(static_cast<double>(j));
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(jacobi);
    nodes.assign(solver.eigenvalues().data(), solver.eigenvalues().data() + n);
    weights.resize(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) weights[static_cast<std::size_t>(j)] = std::pow(solver.eigenvectors()(0, j), 2);
}

// A curve per radian on the increasing grid theta_o, read at the direction whose k sin theta is q (linear in theta;
// 0 beyond the horizon, the end values beyond the grid).
double at_wavenumber(const std::vector<double>& theta_o, const std::vector<double>& curve, double q, double k) {
    if (!(std::abs(q) < k)) return 0.0;
    const double theta = std::asin(q / k);
    const auto it = std::upper_bound(theta_o.begin(), theta_o.end(), theta);
    if (it == theta_o.begin()) return curve.front();
    if (it == theta_o.end()) return curve.back();
    const auto j = static_cast<std::size_t>(it - theta_o.begin());
    const double t = (theta - theta_o[j - 1]) / (theta_o[j] - theta_o[j - 1]);
    return (1 - t) * curve[j - 1] + t * curve[j];
}

std::vector<double> nominal_at(const std::vector<double>& nominal, const std::vector<std::size_t>& at) {
    std::vector<double> out;
    for (const std::size_t j : at) out.push_back(nominal[j]);
    return out;
}

// The lobe at the incidence whose horizontal wavenumber is k0 + u, on the directions theta_o[at] (increasing). It is
// the nominal curve shifted by u in k sin theta_o times a factor that changes slowly with theta_o (the lobe's
// dependence on the incidence other than through k sin theta_o - K): the model is evaluated on every 8th direction of
// each run of neighbouring directions (and the runs' ends) and the factor interpolated linearly between, if the
// interpolation's error, estimated where a grid twice as coarse misses the computed values (a quarter of that:
// linear interpolation's error falls 4-fold when the step halves; the worst relative error over the directions where
// the lobe is >= 1e-3 of its peak), is <= kBlurInterpolationTolerance; otherwise on all of them. At most two calls:
// a model's cost per call (its normalisation) matters as much as per direction.
inline constexpr double kBlurInterpolationTolerance = 1e-4;
inline constexpr std::size_t kBlurStride = 8;
std::vector<double> side_lobe(const LobeAtIncidence& lobe, const std::vector<double>& nominal,
                              const std::vector<double>& theta_o, const std::vector<std::size_t>& at, double k,
                              double k0, double u) {
    const double theta = std::asin((k0 + u) / k);  // |k0 + u| < k where the weight is > 0
    const double peak = *std::max_element(nominal.begin(), nominal.end());
    const double floor = 1e-12 * peak + std::numeric_limits<double>::min();
    std::vector<double> shifted(at.size()), value(at.size()), factor(at.size());
    for (std::size_t i = 0; i < at.size(); ++i)
        shifted[i] = at_wavenumber(theta_o, nominal, k * std::sin(theta_o[at[i]]) - u, k);
    std::vector<char> known(at.size(), 0);
    // The model at the positions `which` of `at` not yet known (a negative incidence read from mirrored directions).
    const auto evaluate = [&](const std::vector<std::size_t>& which) {
        std::vector<std::size_t> todo;
        std::vector<double> directions;
        for (const std::size_t i : which)
            if (!known[i]) {
                todo.push_back(i);
                directions.push_back(theta >= 0 ? theta_o[at[i]] : -theta_o[at[i]]);
            }
        if (todo.empty()) return;
        const std::vector<double> curve = lobe(std::abs(theta), directions);
        if (curve.size() != todo.size())
            fail("beam_blurred: the lobe gave {} values for {} directions", curve.size(), todo.size());
        for (std::size_t t = 0; t < todo.size(); ++t) {
            value[todo[t]] = curve[t];
            factor[todo[t]] = (curve[t] + floor) / (shifted[todo[t]] + floor);
            known[todo[t]] = 1;
        }
    };
    // The positions on stride s: each run's first, every s-th after it, and its last.
    const auto grid = [&](std::size_t s) {
        std::vector<std::size_t> which;
        std::size_t start = 0;
        for (std::size_t i = 0; i < at.size(); ++i) {
            if (i > 0 && at[i] != at[i - 1] + 1) start = i;
            const bool last = i + 1 == at.size() || at[i + 1] != at[i] + 1;
            if ((i - start) % s == 0 || last) which.push_back(i);
        }
        return which;
    };
    // The curve from the factor known on `which`, linear between neighbours of the same run.
    const auto interpolated = [&](const std::vector<std::size_t>& which) {
        std::vector<double> out(at.size());
        for (std::size_t w = 0; w < which.size(); ++w) {
            const std::size_t a = which[w];
            out[a] = value[a];
            if (w + 1 == which.size()) break;
            const std::size_t b = which[w + 1];
            if (at[b] - at[a] != b - a) continue;  // different runs
            for (std::size_t i = a + 1; i < b; ++i) {
                const double t = static_cast<double>(i - a) / static_cast<double>(b - a);
                out[i] = ((1 - t) * factor[a] + t * factor[b]) * (shifted[i] + floor) - floor;
            }
        }
        return out;
    };
    const std::vector<std::size_t> sparse = grid(kBlurStride);
    evaluate(sparse);
    const std::vector<double> coarse = interpolated(grid(2 * kBlurStride));
    double error = 0;
    for (const std::size_t i : sparse)
        if (value[i] >= 1e-3 * peak) error = std::max(error, std::abs(coarse[i] - value[i]) / value[i]);
    if (error / 4 <= kBlurInterpolationTolerance) return interpolated(sparse);
    std::vector<std::size_t> all(at.size());
    for (std::size_t i = 0; i < at.size(); ++i) all[i] = i;
    evaluate(all);
    return value;
}

}  // namespace

BlurredLobe beam_blurred(const LobeAtIncidence& lobe, const std::vector<double>& nominal,
                         const std::vector<double>& theta_o, double k, double theta_i, double g,
                         const std::vector<char>& needed) {
    const std::size_t n = theta_o.size();
    if (nominal.size() != n || (!needed.empty() && needed.size() != n))
        fail("beam_blurred: grid of {} directions, nominal lobe of {}, flags {}", n, nominal.size(), needed.size());
    const auto wanted = [&](std::size_t j) { return needed.empty() || needed[j]; };
    for (std::size_t j = 0; j < n; ++j)
        if (!(std::abs(theta_o[j]) <= kPi / 2) || (j > 0 && !(theta_o[j] > theta_o[j - 1])))
            fail("beam_blurred: theta_o must increase within [-90, 90] deg (at {}: {} rad)", j, theta_o[j]);
    if (!(theta_i >= 0 && theta_i < kPi / 2)) fail("beam_blurred: theta_i must be in [0, 90) deg, got {} rad", theta_i);
    if (!(k > 0) || !(g > 0) || !std::isfinite(k) || !std::isfinite(g))
        fail("beam_blurred: k ({} rad/um) and the beam width ({} um) must be > 0", k, g);
    const double k0 = k * std::sin(theta_i), sigma = 1.0 / g;
    // The weight of the plane wave K = k0 + u: |A|^2 cos theta(K) (0 beyond the horizon).
    const auto weight = [&](double u) {
        const double kx = k0 + u;
        return std::abs(kx) < k ? std::exp(-0.5 * u * u * g * g) * std::sqrt(1.0 - kx * kx / (k * k)) : 0.0;
    };
    // The nominal curve averaged over shifts u in k sin theta_o with weights c (normalised).
    const auto shifted = [&](const std::vector<double>& u, const std::vector<double>& c, std::size_t j) {
        const double q = k * std::sin(theta_o[j]);
        double sum = 0, total = 0;
        for (std::size_t m = 0; m < u.size(); ++m) {
            sum += c[m] * at_wavenumber(theta_o, nominal, q - u[m], k);
            total += c[m];
        }
        return sum / total;
    };
    // Where the rule's error is estimated: the nominal curve >= 1 % of its peak outside the specular zone.
    const double zone = 4.0 / (k * g * std::cos(theta_i));
    double peak = 0;
    for (std::size_t j = 0; j < n; ++j)
        if (std::abs(theta_o[j] - theta_i) >= zone) peak = std::max(peak, nominal[j]);
    std::vector<std::size_t> judged;
    for (std::size_t j = 0; j < n; ++j)
        if (wanted(j) && std::abs(theta_o[j] - theta_i) >= zone && peak > 0 && nominal[j] >= 0.01 * peak)
            judged.push_back(j);
    std::vector<double> fine_u, fine_c;
    for (int m = -48; m <= 48; ++m) {
        fine_u.push_back(m * sigma / 8);
        fine_c.push_back(weight(fine_u.back()) * (std::abs(m) == 48 ? 0.5 : 1.0));
    }
    std::vector<double> fine(judged.size());
    for (std::size_t i = 0; i < judged.size(); ++i) fine[i] = shifted(fine_u, fine_c, judged[i]);
    BlurredLobe out;
    std::vector<double> x, w, u, c;
    for (const int nodes : {3, 5, 9, 17}) {
        gauss_hermite(nodes, x, w);
        u.clear();
        c.clear();
        for (std::size_t m = 0; m < x.size(); ++m) {
            u.push_back(x[m] * sigma);
            c.push_back(w[m] * weight(u.back()) / std::exp(-0.5 * x[m] * x[m]));
        }
        std::vector<double> errors;
        for (std::size_t i = 0; i < judged.size(); ++i)
            if (fine[i] > 0) errors.push_back(std::abs(shifted(u, c, judged[i]) / fine[i] - 1.0));
        out.nodes = nodes;
        out.rule_error = errors.empty() ? 0.0 : median(errors);
        if (out.rule_error <= kBlurRuleTolerance) break;
    }
    // The model at each node's incidence on the directions wanted, weighted; the middle node (u = 0) is the nominal.
    std::vector<std::size_t> at;
    for (std::size_t j = 0; j < n; ++j)
        if (wanted(j)) at.push_back(j);
    std::vector<double> sum(at.size(), 0.0);
    double total = 0;
    for (std::size_t m = 0; m < u.size() && !at.empty(); ++m) {
        if (!(c[m] > 0)) continue;
        const std::vector<double> curve =
            2 * m + 1 == u.size() ? nominal_at(nominal, at) : side_lobe(lobe, nominal, theta_o, at, k, k0, u[m]);
        for (std::size_t i = 0; i < at.size(); ++i) sum[i] += c[m] * curve[i];
        total += c[m];
    }
    out.intensity_per_rad = nominal;
    for (std::size_t i = 0; i < at.size(); ++i) out.intensity_per_rad[at[i]] = sum[i] / total;
    return out;
}

double near_specular_half_width_rad(const reference::StatisticalResult& reference) {
    return 2.0 * reference.beam_half_width_rad;
}

void mark_near_specular(BinnedCurves& b, double theta_i_rad, double half_width_rad, double bin_rad) {
    b.near_specular.assign(b.theta_o_rad.size(), 0);
    b.near_specular_bins = 0;
    for (std::size_t i = 0; i < b.theta_o_rad.size(); ++i)
        if (std::abs(b.theta_o_rad[i] - theta_i_rad) < half_width_rad + 0.5 * bin_rad) {
            b.near_specular[i] = 1;
            ++b.near_specular_bins;
        }
}

namespace {

// The reference's incoherent part binned as the comparison bins it, the bins inside the beam's angular spread left
// out, with the models' curves.
BinnedCurves comparison_bins(const reference::StatisticalResult& reference,
                             const std::vector<std::vector<double>>& models, const ProfileStudy& study,
                             double lambda_nm, double theta_i_deg) {
    const double k = 2 * kPi / (lambda_nm * 1e-3), bin = study.criteria.bin_deg * kDegree;
    BinnedCurves b = bin_curves(reference.theta_o_rad, reference.incoherent, reference.incoherent_stderr, models, bin,
                                k, study.beam_width_um);
    mark_near_specular(b, theta_i_deg * kDegree, near_specular_half_width_rad(reference), bin);
    return b;
}

// The reference's median relative standard error over the bins a comparison would use.
double reference_rel_stderr(const reference::StatisticalResult& reference, const ProfileStudy& study,
                            double lambda_nm, double theta_i_deg) {
    const BinnedCurves b = comparison_bins(reference, {}, study, lambda_nm, theta_i_deg);
    const CurveComparison c = compare_curves(b.theta_o_rad, b.reference, b.reference_stderr, b.reference,
                                             study.criteria, b.near_specular);
    return c.directions_used > 0 ? c.reference_median_rel_stderr : std::numeric_limits<double>::infinity();
}

// The directions of the bins a comparison can use (outside the specular zone, the reference >= peak_fraction of its
// peak): where the models are averaged over the beam.
std::vector<char> compared_directions(const reference::StatisticalResult& reference, const ProfileStudy& study,
                                      double lambda_nm, double theta_i_deg) {
    const BinnedCurves b = comparison_bins(reference, {}, study, lambda_nm, theta_i_deg);
    const double peak = b.reference.empty() ? 0.0 : *std::max_element(b.reference.begin(), b.reference.end());
    std::vector<char> needed(reference.theta_o_rad.size(), 0);
    for (std::size_t i = 0; i < b.reference.size(); ++i) {
        if (b.near_specular[i] || !(b.reference[i] >= study.criteria.peak_fraction * peak)) continue;
        const std::size_t end = i + 1 < b.first_direction.size() ? b.first_direction[i + 1] : needed.size();
        std::fill(needed.begin() + static_cast<std::ptrdiff_t>(b.first_direction[i]),
                  needed.begin() + static_cast<std::ptrdiff_t>(end), 1);
    }
    return needed;
}

// With a target: after each round, how many more realizations the reference needs, from its standard error falling
// as 1 / sqrt(n) (10 % margin, at most doubling per round: the estimate is noisy); a line with the ETA per round.
std::function<std::size_t(const reference::StatisticalResult&)> realizations_wanted(const ProfileStudy& study,
                                                                                   const ProfileCase& pc) {
    const auto start = std::make_shared<std::chrono::steady_clock::time_point>(std::chrono::steady_clock::now());
    const double lambda = pc.wavelength_nm, theta_i = pc.theta_i_deg;
    const std::string label = fmt::format("validity: {} nm, theta_i {} deg, {}", lambda, theta_i,
                                          to_string(pc.polarisation));
    return [&study, start, lambda, theta_i, label](const reference::StatisticalResult& r) -> std::size_t {
        const double stderr_now = reference_rel_stderr(r, study, lambda, theta_i);
        const double n = static_cast<double>(r.realizations);
        if (stderr_now <= study.target_rel_stderr) return 0;
        const double needed = std::isfinite(stderr_now)
                                  ? std::ceil(1.1 * n * std::pow(stderr_now / study.target_rel_stderr, 2))
                                  : 2 * n;
        const double capped = std::min(needed, static_cast<double>(study.statistical.realizations));
        const std::size_t more = static_cast<std::size_t>(std::max(1.0, std::min(capped - n, n)));
        if (study.progress) {
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - *start).count();
            std::fprintf(stderr, "%s: %zu realizations, reference median standard error %.3g %% (target %.3g %%): "
                                 "about %.0f in all, ETA %s\n",
                         label.c_str(), r.realizations, 100 * stderr_now, 100 * study.target_rel_stderr, capped,
                         format_duration(seconds / n * (capped - n)).c_str());
            std::fflush(stderr);
        }
        return more;
    };
}

// The far field a flat profile of the same length and sampling diffracts at its ends: its pattern against that of
// one twice as long (whose ends lie where the beam is e^-3 times weaker), per radian.
std::vector<double> edge_diffraction(const material::Conductor& conductor, const reference::Exact1dOptions& options,
                                     double length_um) {
    const auto flat = [&](double length) {
        return reference::solve_exact_1d(reference::flat_profile(options, length), conductor, options).intensity_per_rad();
    };
    std::vector<double> edge = flat(length_um);
    const std::vector<double> longer = flat(2 * length_um);
    for (std::size_t j = 0; j < edge.size(); ++j) edge[j] = std::abs(edge[j] - longer[j]);
    return edge;
}

}  // namespace

void require_valid_criteria(const Criteria& c, const reference::OptionNames& names) {
    if (!(c.tolerance > 0 && c.tolerance < 1)) fail("{} must be in (0, 1), got {}", names.tolerance, c.tolerance);
    if (!(c.bin_deg >= 0 && c.bin_deg <= 30)) fail("{} must be in [0, 30] degrees, got {}", names.bin_deg, c.bin_deg);
    if (!(c.max_reference_stderr > 0 && c.max_reference_stderr <= 1))
        fail("{} must be in (0, 1], got {}", names.max_reference_stderr, c.max_reference_stderr);
}

std::vector<ProfileCase> profile_validity(const surface::RadialStatistics& statistics,
                                          const material::Conductor& conductor, const ProfileStudy& study) {
    require_valid_criteria(study.criteria, study.option_names);
    require_thread_count(study.statistical.threads, study.option_names.threads.c_str());
    require_list_size(study.wavelengths_nm.size(), study.option_names.wavelength.c_str());
    require_list_size(study.theta_i_deg.size(), "theta_i_deg");
    if (study.wavelengths_nm.empty()) fail("validity: no wavelengths given");
    if (study.theta_i_deg.empty()) fail("validity: no angles of incidence given");
    if (study.polarisations.empty()) fail("validity: no polarisations given");
    for (const double theta : study.theta_i_deg)
        if (!(theta >= 0 && theta < 90)) fail("validity: theta_i must be in [0, 90) degrees, got {}", theta);
    for (const double lambda : study.wavelengths_nm)
        if (!(lambda > 0) || !std::isfinite(lambda)) fail("validity: wavelength must be > 0 nm, got {}", lambda);
    if (!(study.target_rel_stderr >= 0 && study.target_rel_stderr < 1))
        fail("validity: the target standard error must be in [0, 1), got {}", study.target_rel_stderr);
    const std::vector<bsdf::ProfileModel> model_kinds{bsdf::ProfileModel::ghs, bsdf::ProfileModel::ghs_ssa,
                                                      bsdf::ProfileModel::kirchhoff};
    const auto case_options = [&](double lambda, double theta_i, bsdf::ProfilePolarisation polarisation) {
        reference::Exact1dOptions options;
        options.lambda_nm = lambda;
        options.theta_i_rad = theta_i * kDegree;
        options.polarisation = polarisation == bsdf::ProfilePolarisation::s ? reference::Polarisation::s
                                                                            : reference::Polarisation::p;
        options.beam_width_um = study.beam_width_um;
        options.points_per_wavelength = study.points_per_wavelength;
        options.option_names = study.option_names;
        return options;
    };
    // Every case's sampling, beam, material and one solve's memory before the first starts (a case refused half-way
    // through the run named a derived value after the progress had begun).
    for (const double lambda : study.wavelengths_nm)
        for (const double theta_i : study.theta_i_deg) {
            bsdf::require_profile_wavelength(lambda, study.option_names.wavelength);  // the models' range
            const auto options = case_options(lambda, theta_i, study.polarisations.front());
            reference::require_exact_1d_memory(reference::flat_profile(options, study.statistical.length_um), conductor,
                                               options, 1);
        }
    const std::size_t total = study.wavelengths_nm.size() * study.theta_i_deg.size() * study.polarisations.size();
    Progress progress("validity", total, study.progress);
    std::vector<ProfileCase> cases;
    for (const double lambda : study.wavelengths_nm)
        for (const double theta_i : study.theta_i_deg)
            for (const auto polarisation : study.polarisations) {
                if (interrupt_requested()) return cases;
                const reference::Exact1dOptions options = case_options(lambda, theta_i, polarisation);
                ProfileCase pc;
                pc.wavelength_nm = lambda;
                pc.theta_i_deg = theta_i;
                pc.polarisation = polarisation;
                reference::StatisticalOptions statistical = study.statistical;
                if (study.target_rel_stderr > 0) statistical.more = realizations_wanted(study, pc);
                pc.reference = reference::solve_exact_1d_statistics(statistics, conductor, options, statistical);
                if (interrupt_requested()) return cases;  // a case cut short is dropped
                pc.reference_rel_stderr = reference_rel_stderr(pc.reference, study, lambda, theta_i);
                pc.target_reached = pc.reference_rel_stderr <= study.target_rel_stderr || study.target_rel_stderr == 0;
                pc.reference_energy = trapezoid(pc.reference.theta_o_rad, pc.reference.intensity);
                std::vector<std::vector<double>> curves;
                const double k = 2 * kPi / (lambda * 1e-3);
                const std::vector<char> needed = compared_directions(pc.reference, study, lambda, theta_i);
                // A model's lobe at any incidence on any directions (the beam's kernel needs its neighbours).
                using MakeLobe = std::function<bsdf::ProfileLobe(double, const std::vector<double>&)>;
                const auto add = [&](const std::string& name, const MakeLobe& make) {
                    const bsdf::ProfileLobe lobe = make(theta_i * kDegree, pc.reference.theta_o_rad);
                    ModelResult m;
                    m.model = name;
                    m.coherent = lobe.coherent;
                    m.model_energy = lobe.energy ? *lobe.energy
                                                 : lobe.coherent + trapezoid(pc.reference.theta_o_rad,
                                                                             lobe.intensity_per_rad);
                    const BlurredLobe blurred = beam_blurred(
                        [&make](double theta, const std::vector<double>& theta_o) {
                            return make(theta, theta_o).intensity_per_rad;
                        },
                        lobe.intensity_per_rad, pc.reference.theta_o_rad, k, theta_i * kDegree, study.beam_width_um,
                        needed);
                    m.incoherent_per_rad = blurred.intensity_per_rad;
                    m.own_rel_uncertainty = blurred.rule_error;
                    m.blur_nodes = blurred.nodes;
                    curves.push_back(m.incoherent_per_rad);
                    pc.models.push_back(std::move(m));
                };
                for (const auto kind : model_kinds) {
                    bsdf::ProfileModelOptions model_options;
                    model_options.model = kind;
                    add(bsdf::to_string(kind), [&, model_options](double theta, const std::vector<double>& theta_o) {
                        return bsdf::profile_lobe(statistics, conductor, lambda, theta, polarisation, model_options,
                                                  theta_o);
                    });
                }
                try {
                    add("ggx_stats", [&](double theta, const std::vector<double>& theta_o) {
                        return bsdf::ggx_profile_lobe(statistics, conductor, lambda, theta, polarisation, theta_o);
                    });
                } catch (const Error& e) {
                    pc.not_compared.push_back(e.what());
                }
                try {
                    add("two_scale", [&](double theta, const std::vector<double>& theta_o) {
                        return bsdf::two_scale_profile_lobe(statistics, conductor, lambda, theta, polarisation,
                                                            theta_o);
                    });
                } catch (const Error& e) {
                    pc.not_compared.push_back(e.what());
                }
                curves.push_back(edge_diffraction(conductor, options, study.statistical.length_um));
                pc.binned = comparison_bins(pc.reference, curves, study, lambda, theta_i);
                const CurveComparison edge = compare_curves(pc.binned.theta_o_rad, pc.binned.reference,
                                                            pc.binned.reference_stderr, pc.binned.models.back(),
                                                            study.criteria, pc.binned.near_specular);
                pc.binned.models.pop_back();
                if (edge.directions_used > 0) {
                    std::vector<double> ratios;
                    for (const double d : edge.rel_deviation) ratios.push_back(1.0 + d);
                    pc.edge_rel_error = median(ratios);
                }
                for (std::size_t m = 0; m < pc.models.size(); ++m)
                    pc.models[m].comparison = compare_curves(pc.binned.theta_o_rad, pc.binned.reference,
                                                             pc.binned.reference_stderr, pc.binned.models[m],
                                                             study.criteria, pc.binned.near_specular);
                const std::string problem =
                    pc.edge_rel_error > study.criteria.tolerance
                        ? fmt::format("the profile's ends, {:.3g} beam widths either side of the beam centre, "
                                      "diffract {} of the reference's median in the bins used, above the tolerance "
                                      "{}: use a longer {} or a narrower {}",
                                      0.5 * study.statistical.length_um / study.beam_width_um,
                                      percent(pc.edge_rel_error), percent(study.criteria.tolerance),
                                      study.option_names.length, study.option_names.beam_width)
                        : std::string();
                pc.verdict = decide(pc.models, study.criteria, problem, study.option_names);
                std::vector<ModelResult> render;
                for (const ModelResult& m : pc.models)
                    if (m.model != "kirchhoff") render.push_back(m);
                pc.render_verdict = decide(render, study.criteria, problem, study.option_names);
                cases.push_back(std::move(pc));
                progress.advance();
            }
    progress.finish();
    return cases;
}

}  // namespace surfscatter::validity
