#include "surfscatter/inverse/fit_report.hpp"

#include <fmt/format.h>

namespace surfscatter::inverse {

namespace {

nlohmann::json optional_number(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nlohmann::json(); }

std::string misfit_text(const ModelFit& fit) {
    return fmt::format("{} {:.4g}", fit.with_errors ? "chi2/dof" : "relative rms", fit.misfit);
}

}  // namespace

nlohmann::json fit_json(const BrdfData& data, const FitOptions& options, const FitResult& result) {
    nlohmann::json j;
    j["data"] = {{"source", data.source}, {"rows", data.size()}, {"with_errors", !data.brdf_stderr.empty()}};
    j["material"] = options.material;
    j["psd"] = bsdf::to_string(options.psd);
    j["anisotropic"] = options.anisotropic;
    // Profile data (1-D, docs/FIT.md "Profiles"): the polarisation, else null.
    j["profile"] = options.profile ? nlohmann::json(*options.profile == bsdf::ProfilePolarisation::s ? "s" : "p")
                                   : nlohmann::json();
    j["fixed"] = options.fixed;
    j["models"] = nlohmann::json::array();
    for (const ModelFit& fit : result.fits) {
        nlohmann::json m;
        m["model"] = bsdf::to_string(fit.model);
        for (const ParameterEstimate& p : fit.parameters) {
            nlohmann::json e = {{"value", p.value},
                                {"standard_error", optional_number(p.standard_error)},
                                {"fixed", p.fixed},
                                {"constrained", p.constrained}};
            if (!p.note.empty()) e["note"] = p.note;
            m["parameters"][p.name] = e;
        }
        m["free"] = fit.free;
        nlohmann::json rows = nlohmann::json::array();
        for (const auto& row : fit.correlation) {
            nlohmann::json r = nlohmann::json::array();
            for (const auto& c : row) r.push_back(optional_number(c));
            rows.push_back(r);
        }
        m["correlation"] = rows;
        m["degenerate_directions"] = fit.degenerate_directions;
        m["misfit"] = {{"kind", fit.with_errors ? "chi2_per_dof" : "relative_rms"},
                       {"value", fit.misfit},
                       {"sum_squares", fit.sum_squares},
                       {"dof", fit.dof}};
        nlohmann::json worst = nlohmann::json::array();
        for (const std::size_t w : fit.worst)
            worst.push_back({{"row", data.line.empty() ? static_cast<int>(w + 1) : data.line[w]},
                             {"wavelength_nm", data.wavelength_nm[w]},
                             {"theta_i_deg", data.theta_i_deg[w]},
                             {"phi_i_deg", data.phi_i_deg[w]},
                             {"theta_o_deg", data.theta_o_deg[w]},
                             {"phi_o_deg", data.phi_o_deg[w]},
                             {"brdf", data.brdf[w]},
                             {"fit", fit.fitted[w]},
                             {"residual", fit.residual[w]}});
        m["worst_directions"] = worst;
        m["evaluations"] = fit.evaluations;
        m["cpu_seconds"] = fit.cpu_seconds;
        m["notes"] = fit.notes;
        m["summary"] = summary_line(fit);
        j["models"].push_back(m);
    }
    j["best"] = bsdf::to_string(result.fits[result.best].model);
    nlohmann::json same = nlohmann::json::array();
    for (const std::size_t m : result.indistinguishable) same.push_back(bsdf::to_string(result.fits[m].model));
    j["indistinguishable_from_best"] = same;
    j["verdict"] = result.verdict;
    return j;
}

std::string fit_csv(const BrdfData& data, const FitResult& result) {
    const bool errors = !data.brdf_stderr.empty();
    std::string out = "wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf";
    if (errors) out += ",brdf_stderr";
    for (const ModelFit& fit : result.fits)
        out += fmt::format(",{0}_fit,{0}_residual", bsdf::to_string(fit.model));
    out += "\n";
    for (std::size_t j = 0; j < data.size(); ++j) {
        out += fmt::format("{},{},{},{},{},{}", data.wavelength_nm[j], data.theta_i_deg[j], data.phi_i_deg[j],
                           data.theta_o_deg[j], data.phi_o_deg[j], data.brdf[j]);
        if (errors) out += fmt::format(",{}", data.brdf_stderr[j]);
        for (const ModelFit& fit : result.fits) out += fmt::format(",{},{}", fit.fitted[j], fit.residual[j]);
        out += "\n";
    }
    return out;
}

std::string summary_line(const ModelFit& fit) {
    std::string line = bsdf::to_string(fit.model) + ":";
    for (const ParameterEstimate& p : fit.parameters) {
        if (p.fixed)
            line += fmt::format(" {} {:.4g} (fixed),", p.name, p.value);
        else if (p.constrained)
            line += fmt::format(" {} {:.4g} +- {:.2g},", p.name, p.value, p.standard_error.value_or(0.0));
        else
            line += fmt::format(" {} unconstrained ({:.4g}: {}),", p.name, p.value, p.note);
    }
    return line + " " + misfit_text(fit);
}

}  // namespace surfscatter::inverse
