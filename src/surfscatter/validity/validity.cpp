#include "surfscatter/validity/validity.hpp"

#include <algorithm>
#include <cmath>

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
                               const Criteria& criteria) {
    if (reference.size() != theta_o_rad.size() || reference_stderr.size() != theta_o_rad.size() ||
        model.size() != theta_o_rad.size())
        fail("compare_curves: grid of {} directions, reference {}, its standard errors {}, model {}",
             theta_o_rad.size(), reference.size(), reference_stderr.size(), model.size());
    const double peak = reference.empty() ? 0.0 : *std::max_element(reference.begin(), reference.end());
    CurveComparison c;
    std::vector<double> errors, stderrs;
    for (std::size_t j = 0; j < reference.size(); ++j) {
        if (!(peak > 0) || reference[j] < criteria.peak_fraction * peak) continue;
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
    }
    c.directions_used = errors.size();
    if (!errors.empty()) {
        c.median_rel_error = median(errors);
        c.reference_median_rel_stderr = median(stderrs);
    }
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
        out.theta_o_rad.push_back(centre);
        out.reference.push_back(ref / count);
        out.reference_stderr.push_back(std::sqrt(var / count / independent));
        for (std::size_t m = 0; m < models.size(); ++m) out.models[m].push_back(sums[m] / count);
        j = end;
    }
    return out;
}

Verdict decide(const std::vector<ModelResult>& models, const Criteria& criteria) {
    Verdict v;
    if (models.empty()) fail("decide: no models to compare");
    const CurveComparison& c = models.front().comparison;  // the same reference directions for every model
    if (c.directions_used == 0) {
        v.text = fmt::format("nothing can be concluded: no direction has a reference with a standard error within {} "
                             "of its value ({} excluded); use more realizations",
                             percent(criteria.max_reference_stderr), c.directions_excluded);
        return v;
    }
    std::string ruled_out;
    for (const ModelResult& m : models)
        if (m.comparison.median_rel_error > criteria.tolerance + 2 * c.reference_median_rel_stderr) {
            v.ruled_out.push_back(m.model);
            ruled_out += fmt::format(" {} ({})", m.model, percent(m.comparison.median_rel_error));
        }
    if (!ruled_out.empty()) ruled_out = "; ruled out:" + ruled_out;
    if (c.reference_median_rel_stderr > criteria.tolerance) {
        v.text = fmt::format("no model can be certified: the reference's median standard error {} exceeds the "
                             "tolerance {} (use more realizations){}",
                             percent(c.reference_median_rel_stderr), percent(criteria.tolerance), ruled_out);
        return v;
    }
    v.conclusive = true;
    const auto best = std::min_element(models.begin(), models.end(), [](const ModelResult& a, const ModelResult& b) {
        return a.comparison.median_rel_error < b.comparison.median_rel_error;
    });
    v.best_model = best->model;
    const double allowed = criteria.tolerance + c.reference_median_rel_stderr;
    v.trusted = best->comparison.median_rel_error <= allowed;
    for (const ModelResult& m : models)
        if (m.comparison.median_rel_error <= allowed) v.within_tolerance.push_back(m.model);
    if (v.trusted) {
        v.text = fmt::format("trust {} (median error {}, worst {}; reference uncertainty {})", best->model,
                             percent(best->comparison.median_rel_error), percent(best->comparison.worst_rel_error),
                             percent(c.reference_median_rel_stderr));
        if (v.within_tolerance.size() > 1) {
            v.text += fmt::format("; within {} too:", percent(allowed));
            for (const std::string& name : v.within_tolerance)
                if (name != best->model) v.text += " " + name;
        }
        v.text += ruled_out;
    } else {
        v.text = fmt::format("no model is within {} (tolerance + reference uncertainty): the closest is {} "
                             "(median error {}, worst {})",
                             percent(allowed), best->model, percent(best->comparison.median_rel_error),
                             percent(best->comparison.worst_rel_error));
        v.text += ruled_out;
    }
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

void require_valid_criteria(const Criteria& c, const char* tolerance_name, const char* bin_name,
                            const char* stderr_name) {
    if (!(c.tolerance > 0 && c.tolerance < 1)) fail("{} must be in (0, 1), got {}", tolerance_name, c.tolerance);
    if (!(c.bin_deg >= 0 && c.bin_deg <= 30)) fail("{} must be in [0, 30] degrees, got {}", bin_name, c.bin_deg);
    if (!(c.max_reference_stderr > 0 && c.max_reference_stderr <= 1))
        fail("{} must be in (0, 1], got {}", stderr_name, c.max_reference_stderr);
}

std::vector<ProfileCase> profile_validity(const surface::RadialStatistics& statistics,
                                          const material::Conductor& conductor, const ProfileStudy& study) {
    require_valid_criteria(study.criteria, "tolerance", "bin_deg", "max_reference_stderr");
    require_thread_count(study.statistical.threads, "threads");
    require_list_size(study.wavelengths_nm.size(), "wavelengths_nm");
    require_list_size(study.theta_i_deg.size(), "theta_i_deg");
    if (study.wavelengths_nm.empty()) fail("validity: no wavelengths given");
    if (study.theta_i_deg.empty()) fail("validity: no angles of incidence given");
    if (study.polarisations.empty()) fail("validity: no polarisations given");
    for (const double theta : study.theta_i_deg)
        if (!(theta >= 0 && theta < 90)) fail("validity: theta_i must be in [0, 90) degrees, got {}", theta);
    for (const double lambda : study.wavelengths_nm)
        if (!(lambda > 0) || !std::isfinite(lambda)) fail("validity: wavelength must be > 0 nm, got {}", lambda);
    const std::vector<bsdf::ProfileModel> model_kinds{bsdf::ProfileModel::ghs, bsdf::ProfileModel::ghs_ssa,
                                                      bsdf::ProfileModel::kirchhoff};
    const std::size_t total = study.wavelengths_nm.size() * study.theta_i_deg.size() * study.polarisations.size();
    Progress progress("validity", total, study.progress);
    std::vector<ProfileCase> cases;
    for (const double lambda : study.wavelengths_nm)
        for (const double theta_i : study.theta_i_deg)
            for (const auto polarisation : study.polarisations) {
                if (interrupt_requested()) return cases;
                reference::Exact1dOptions options;
                options.lambda_nm = lambda;
                options.theta_i_rad = theta_i * kDegree;
                options.polarisation = polarisation == bsdf::ProfilePolarisation::s ? reference::Polarisation::s
                                                                                    : reference::Polarisation::p;
                options.beam_width_um = study.beam_width_um;
                options.points_per_wavelength = study.points_per_wavelength;
                ProfileCase pc;
                pc.wavelength_nm = lambda;
                pc.theta_i_deg = theta_i;
                pc.polarisation = polarisation;
                pc.reference = reference::solve_exact_1d_statistics(statistics, conductor, options, study.statistical);
                if (pc.reference.realizations < study.statistical.realizations) return cases;  // interrupted
                pc.reference_energy = trapezoid(pc.reference.theta_o_rad, pc.reference.intensity);
                std::vector<std::vector<double>> curves;
                for (const auto kind : model_kinds) {
                    bsdf::ProfileModelOptions model_options;
                    model_options.model = kind;
                    const auto lobe = bsdf::profile_lobe(statistics, conductor, lambda, theta_i * kDegree,
                                                         polarisation, model_options, pc.reference.theta_o_rad);
                    ModelResult m;
                    m.model = bsdf::to_string(kind);
                    m.coherent = lobe.coherent;
                    m.model_energy = lobe.coherent + trapezoid(pc.reference.theta_o_rad, lobe.intensity_per_rad);
                    m.incoherent_per_rad = lobe.intensity_per_rad;
                    curves.push_back(lobe.intensity_per_rad);
                    pc.models.push_back(std::move(m));
                }
                pc.binned = bin_curves(pc.reference.theta_o_rad, pc.reference.incoherent,
                                       pc.reference.incoherent_stderr, curves, study.criteria.bin_deg * kDegree,
                                       2 * kPi / (lambda * 1e-3), study.beam_width_um);
                for (std::size_t m = 0; m < pc.models.size(); ++m)
                    pc.models[m].comparison = compare_curves(pc.binned.theta_o_rad, pc.binned.reference,
                                                             pc.binned.reference_stderr, pc.binned.models[m],
                                                             study.criteria);
                pc.verdict = decide(pc.models, study.criteria);
                cases.push_back(std::move(pc));
                progress.advance();
            }
    progress.finish();
    return cases;
}

}  // namespace surfscatter::validity
