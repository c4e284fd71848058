// surfscatter validity: which model to trust for a surface (docs/VALIDITY.md). Profiles cut through KC/Gaussian
// statistics: the 1-D GHS, SSA and Kirchhoff forms against exact-1d's average over random profiles, per wavelength,
// incidence and polarisation. Writes OUT.csv (one row per model and case), OUT.json (the table, the verdicts and the
// curves), OUT_slices.png and OUT_error_map.png, and a summary on stdout.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "list_options.hpp"
#include "profile_surface_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/validity/validity.hpp"

namespace surfscatter::cli {

namespace {

struct ValidityArgs {
    SurfaceArgs surface;
    std::string material, polarisation = "both", output;
    std::vector<double> wavelengths, theta_i;
    double length = 0, beam_width = 0, points_per_wavelength = 10;
    double tolerance = 0.10, max_reference_stderr = 0.25, bin_deg = 3;
    long long realizations = 0, seed = 1;
    int threads = 0;
};

std::string csv_table(const std::vector<validity::ProfileCase>& cases) {
    std::string out = "model,wavelength_nm,theta_i_deg,polarisation,median_rel_error,worst_rel_error,"
                      "worst_theta_o_deg,directions_used,directions_excluded,reference_median_rel_stderr,"
                      "model_energy,reference_energy,trusted,verdict\n";
    for (const auto& row : validity::table(cases)) {
        const auto& cmp = row.comparison;
        out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"\n", row.model, format_number(row.wavelength_nm),
                           format_number(row.theta_i_deg), row.polarisation, format_number(cmp.median_rel_error),
                           format_number(cmp.worst_rel_error), format_number(cmp.worst_theta_o_rad / kDegree),
                           cmp.directions_used, cmp.directions_excluded,
                           format_number(cmp.reference_median_rel_stderr), format_number(row.model_energy),
                           format_number(row.reference_energy), row.trusted ? 1 : 0, row.verdict);
    }
    return out;
}

nlohmann::json json_report(const std::vector<validity::ProfileCase>& cases, const ValidityArgs& a,
                           const std::string& surface, const std::string& material) {
    nlohmann::json j;
    j["surface"] = surface;
    j["material"] = material;
    j["criteria"] = {{"peak_fraction", validity::Criteria{}.peak_fraction}, {"max_reference_stderr", a.max_reference_stderr},
                     {"tolerance", a.tolerance}, {"bin_deg", a.bin_deg}};
    j["reference"] = {{"solver", "exact-1d"},         {"length_um", a.length},
                      {"beam_width_um", a.beam_width}, {"realizations", a.realizations},
                      {"seed", a.seed},                {"points_per_wavelength", a.points_per_wavelength}};
    j["cases"] = nlohmann::json::array();
    for (const auto& c : cases) {
        nlohmann::json jc;
        jc["wavelength_nm"] = c.wavelength_nm;
        jc["theta_i_deg"] = c.theta_i_deg;
        jc["polarisation"] = validity::to_string(c.polarisation);
        jc["reference_energy"] = c.reference_energy;
        jc["verdict"] = {{"conclusive", c.verdict.conclusive}, {"trusted", c.verdict.trusted},
                         {"best_model", c.verdict.best_model}, {"within_tolerance", c.verdict.within_tolerance},
                         {"ruled_out", c.verdict.ruled_out},
                         {"text", c.verdict.text}};
        std::vector<double> theta_deg;
        for (const double t : c.reference.theta_o_rad) theta_deg.push_back(t / kDegree);
        jc["theta_o_deg"] = theta_deg;
        jc["reference_incoherent_per_rad"] = c.reference.incoherent;
        jc["reference_incoherent_stderr_per_rad"] = c.reference.incoherent_stderr;
        std::vector<double> bin_deg;
        for (const double t : c.binned.theta_o_rad) bin_deg.push_back(t / kDegree);
        jc["binned"] = {{"theta_o_deg", bin_deg},
                        {"reference_per_rad", c.binned.reference},
                        {"reference_stderr_per_rad", c.binned.reference_stderr}};
        for (std::size_t m = 0; m < c.models.size(); ++m)
            jc["binned"]["models"][c.models[m].model] = c.binned.models[m];
        for (const auto& m : c.models)
            jc["models"][m.model] = {{"median_rel_error", m.comparison.median_rel_error},
                                     {"worst_rel_error", m.comparison.worst_rel_error},
                                     {"directions_used", m.comparison.directions_used},
                                     {"directions_excluded", m.comparison.directions_excluded},
                                     {"used_bins", m.comparison.used},
                                     {"model_energy", m.model_energy},
                                     {"coherent", m.coherent},
                                     {"incoherent_per_rad", m.incoherent_per_rad}};
        j["cases"].push_back(std::move(jc));
    }
    return j;
}

void print_summary(const std::vector<validity::ProfileCase>& cases) {
    for (const auto& c : cases)
        std::printf("%s nm, theta_i %s deg, %s: %s\n", format_number(c.wavelength_nm).c_str(),
                    format_number(c.theta_i_deg).c_str(), validity::to_string(c.polarisation).c_str(),
                    c.verdict.text.c_str());
}

void run_validity(const ValidityArgs& a) {
    if (!a.surface.psd) fail("validity needs the surface: --psd kc|gaussian --sigma --corr-length [--gamma]");
    const auto statistics = statistics_from(a.surface);
    const auto conductor = material::Conductor::from_name(a.material);
    require_positive(a.length, "--length-um");
    require_positive(a.beam_width, "--beam-width");
    if (a.realizations < 2) fail("--realizations must be at least 2, got {}", a.realizations);
    if (a.seed < 0) fail("--seed must be >= 0, got {}", a.seed);
    require_thread_count(a.threads, "--threads");
    if (!(a.tolerance > 0 && a.tolerance < 1)) fail("--tolerance must be in (0, 1), got {}", a.tolerance);
    if (!(a.bin_deg >= 0 && a.bin_deg <= 30)) fail("--bin-deg must be in [0, 30] degrees, got {}", a.bin_deg);
    if (!(a.max_reference_stderr > 0 && a.max_reference_stderr <= 1))
        fail("--max-reference-stderr must be in (0, 1], got {}", a.max_reference_stderr);

    validity::ProfileStudy study;
    study.wavelengths_nm = a.wavelengths;
    study.theta_i_deg = a.theta_i;
    if (a.polarisation == "both")
        study.polarisations = {bsdf::ProfilePolarisation::s, bsdf::ProfilePolarisation::p};
    else
        study.polarisations = {bsdf::parse_profile_polarisation(a.polarisation, "--polarisation")};
    study.beam_width_um = a.beam_width;
    study.points_per_wavelength = a.points_per_wavelength;
    study.statistical.length_um = a.length;
    study.statistical.realizations = static_cast<std::size_t>(a.realizations);
    study.statistical.seed = static_cast<std::uint64_t>(a.seed);
    study.statistical.threads = a.threads;
    study.criteria.tolerance = a.tolerance;
    study.criteria.max_reference_stderr = a.max_reference_stderr;
    study.criteria.bin_deg = a.bin_deg;
    study.progress = true;
    install_interrupt_handler();
    const auto cases = validity::profile_validity(*statistics, conductor, study);
    const std::size_t asked = a.wavelengths.size() * a.theta_i.size() * study.polarisations.size();
    if (cases.size() < asked)
        std::fprintf(stderr, "surfscatter: interrupted: %s.csv holds %zu of %zu cases\n", a.output.c_str(),
                     cases.size(), asked);
    if (cases.empty()) return;

    const std::string csv_path = a.output + ".csv", json_path = a.output + ".json";
    write_file_atomically(csv_path, csv_table(cases));
    write_file_atomically(json_path, json_report(cases, a,
                                                fmt::format("{}, sigma_h {} um", statistics->cache_key(),
                                                            format_number(statistics->sigma_h())),
                                                conductor.name()).dump() + "\n");
    run_plot_script("validity.py", {json_path, a.output + "_slices.png", a.output + "_error_map.png"});
    print_summary(cases);
    std::printf("wrote %s, %s, %s_slices.png and %s_error_map.png\n", csv_path.c_str(), json_path.c_str(),
                a.output.c_str(), a.output.c_str());
    std::size_t concluded = 0;
    for (const auto& c : cases) concluded += c.verdict.conclusive || !c.verdict.ruled_out.empty() ? 1 : 0;
    // Nothing concluded anywhere (no model certified or ruled out): the reference cannot be trusted at these settings.
    if (concluded == 0 && !interrupt_requested())
        fail("nothing can be concluded: the reference's Monte Carlo error is too large (more --realizations or "
             "--length-um)");
}

const Command command("validity", [](CLI::App& app) {
    auto a = std::make_shared<ValidityArgs>();
    auto* sub = app.add_subcommand(
        "validity", "Which model to trust: the 1-D GHS, SSA and Kirchhoff forms against the exact 1-D solution "
                    "averaged over random profiles, per wavelength, incidence and polarisation (docs/VALIDITY.md)");
    a->surface.add_to(sub, "kc or gaussian PSD of the isotropic surface the random profiles are cuts through");
    sub->add_option("--material", a->material,
                    "perfect, a built-in metal (Ag, Au, Al, Cu, ...) or a .yml/.csv refractive index file")
        ->required();
    add_number_list(sub, "--wavelengths", a->wavelengths, "wavelengths in nm, comma-separated")->required();
    add_number_list(sub, "--theta-i", a->theta_i, "angles of incidence in degrees, comma-separated")->required();
    sub->add_option("--polarisation", a->polarisation, "s | p | both (default)")
        ->check(CLI::IsMember({"s", "p", "both"}));
    sub->add_option("--length-um", a->length, "length of each random profile (um), centred on x = 0")->required();
    sub->add_option("--beam-width", a->beam_width, "Thorsos taper width g along x in um")->required();
    sub->add_option("--realizations", a->realizations, "random profiles per case (>= 2)")->required();
    sub->add_option("--seed", a->seed, "seed of the first profile; profile r uses seed + r (default 1)");
    sub->add_option("--points-per-wavelength", a->points_per_wavelength,
                    "exact-1d solver nodes per wavelength (default 10)");
    sub->add_option("--tolerance", a->tolerance, "median relative error a trusted model keeps within (default 0.1)");
    sub->add_option("--max-reference-stderr", a->max_reference_stderr,
                    "directions whose reference standard error exceeds this fraction of it are left out (default "
                    "0.25)");
    sub->add_option("--bin-deg", a->bin_deg,
                    "theta_o bins the curves are averaged over before comparing, degrees (default 3; 0: none)");
    sub->add_option("--threads", a->threads, "realizations solved at once, 0 = all cores (default)");
    sub->add_option("-o", a->output, "output prefix: OUT.csv, OUT.json, OUT_slices.png, OUT_error_map.png")
        ->required();
    sub->callback([a] { run_validity(*a); });
});

}  // namespace

}  // namespace surfscatter::cli
