// surfscatter validity: which model to trust for a surface (docs/VALIDITY.md). Two routes:
// * profiles (--length-um): profiles cut through KC/Gaussian statistics, the 1-D GHS, SSA, Kirchhoff, GGX and
//   two_scale forms against exact-1d's average over random profiles (--realizations, or until --target-stderr),
//   per wavelength, incidence and polarisation;
// * maps (--surface-file, or --map-size-um for maps synthesised from --psd statistics, elliptical with
//   --corr-length-v / --lay-angle): every 2-D model the factory makes against the maps' Kirchhoff BRDF, per
//   wavelength and incidence (theta_i, phi_i), with Kirchhoff's own validity (validity/map_validity.hpp).
// Writes OUT.csv (one row per model and case), OUT.json (the table, the verdicts and the curves), OUT_slices.png and
// OUT_error_map.png, and a summary on stdout.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "list_options.hpp"
#include "option_scope.hpp"
#include "preparation_options.hpp"
#include "profile_surface_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/validity/map_validity.hpp"
#include "surfscatter/validity/validity.hpp"

namespace surfscatter::cli {

namespace {

constexpr double kDefaultTargetStderrPct = 2;
constexpr long long kDefaultMaxRealizations = 1000;

struct ValidityArgs {
    SurfaceArgs surface;
    std::string material, polarisation = "both", output;
    std::vector<double> wavelengths, theta_i;
    double length = 0, beam_width = 0, points_per_wavelength = 10;
    double tolerance = 0.10, max_reference_stderr = 0.25, bin_deg = 3;
    std::optional<long long> realizations;  // profiles: >= 2, no default; synthesised maps: 1 by default
    long long seed = 1;
    std::optional<double> target_stderr;          // percent
    std::optional<long long> max_realizations;
    int threads = 0;
    // the map route
    std::string surface_file;
    PreparationArgs preparation;
    std::vector<double> phi_i;
    std::optional<double> map_size, corr_length_v, lay_angle, subarea;
    long long map_pixels = 256;
    double max_theta_o = 80;
};

// validity's three surfaces and the options each takes; the others apply to all three.
const std::string kProfiles = "the profiles route (--length-um)", kSynthesised = "synthesised maps (--map-size-um)",
                  kMeasured = "a measured map (--surface-file)";
const std::vector<OptionScope> kValidityScopes = {
    {"--psd", {kProfiles, kSynthesised}},
    {"--sigma", {kProfiles, kSynthesised}},
    {"--corr-length", {kProfiles, kSynthesised}},
    {"--gamma", {kProfiles, kSynthesised}},
    {"--realizations", {kProfiles, kSynthesised}},
    {"--seed", {kProfiles, kSynthesised}},
    {"--length-um", {kProfiles}},
    {"--beam-width", {kProfiles}},
    {"--points-per-wavelength", {kProfiles}},
    {"--polarisation", {kProfiles}},
    {"--target-stderr", {kProfiles}},
    {"--max-realizations", {kProfiles}},
    {"--map-pixels", {kSynthesised}},
    {"--corr-length-v", {kSynthesised}},
    {"--lay-angle", {kSynthesised}, "--corr-length-v", "the surface is isotropic"},
    {"--phi-i", {kSynthesised, kMeasured}},
    {"--subarea-um", {kSynthesised, kMeasured}},
    {"--max-theta-o", {kSynthesised, kMeasured}},
    {"--outliers", {kMeasured}},
    {"--row-alignment", {kMeasured}},
    {"--form", {kMeasured}},
    {"--lambda-s", {kMeasured}},
    {"--lambda-c", {kMeasured}},
};

const std::string& validity_mode(const ValidityArgs& a) {
    if (!a.surface_file.empty()) {
        if (a.map_size) fail("--surface-file is the surface: --map-size-um synthesises one instead, give one or the other");
        return kMeasured;
    }
    return a.map_size ? kSynthesised : kProfiles;
}

// One row per model and case; the map route appends its incidence azimuth and whether the reference is valid.
std::string csv_table(const std::vector<validity::TableRow>& rows, bool map_route) {
    std::string out = "model,wavelength_nm,theta_i_deg,polarisation,median_rel_error,worst_rel_error,"
                      "worst_theta_o_deg,directions_used,directions_excluded,reference_median_rel_stderr,"
                      "model_energy,reference_energy,trusted,verdict";
    out += map_route ? ",phi_i_deg,reference_valid\n" : "\n";
    for (const auto& row : rows) {
        const auto& cmp = row.comparison;
        out += fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"", row.model, format_number(row.wavelength_nm),
                           format_number(row.theta_i_deg), row.polarisation, format_number(cmp.median_rel_error),
                           format_number(cmp.worst_rel_error), format_number(cmp.worst_theta_o_rad / kDegree),
                           cmp.directions_used, cmp.directions_excluded,
                           format_number(cmp.reference_median_rel_stderr), format_number(row.model_energy),
                           format_number(row.reference_energy), row.trusted ? 1 : 0, row.verdict);
        out += map_route ? fmt::format(",{},{}\n", format_number(row.phi_i_deg), row.reference_valid ? 1 : 0) : "\n";
    }
    return out;
}

nlohmann::json verdict_json(const validity::Verdict& v) {
    return {{"conclusive", v.conclusive},
            {"trusted", v.trusted},
            {"best_model", v.best_model},
            {"indistinguishable", v.indistinguishable},
            {"within_tolerance", v.within_tolerance},
            {"ruled_out", v.ruled_out},
            {"reference_problem", v.reference_problem},
            {"text", v.text}};
}

nlohmann::json model_json(const validity::ModelResult& m) {
    return {{"median_rel_error", m.comparison.median_rel_error},
            {"worst_rel_error", m.comparison.worst_rel_error},
            {"directions_used", m.comparison.directions_used},
            {"directions_excluded", m.comparison.directions_excluded},
            {"used_bins", m.comparison.used},
            {"model_energy", m.model_energy},
            {"coherent", m.coherent},
            {"own_rel_uncertainty", m.own_rel_uncertainty},
            {"beam_blur_nodes", m.blur_nodes}};
}

// How the profile route's models are made comparable with the reference's beam (validity::beam_blurred).
std::string beam_note(double beam_width_um) {
    return fmt::format("each model's incoherent part is averaged over the reference beam's incident plane waves, as "
                       "exact-1d's mean is: K = k sin theta weighted by cos theta exp(-(K - k sin theta_i)^2 g^2 / 2), "
                       "a Gaussian of standard deviation 1/g = {:.3g} rad/um in K (docs/VALIDITY.md, \"The beam's "
                       "kernel\"); energies are the plane-wave models'",
                       1.0 / beam_width_um);
}

nlohmann::json json_report(const std::vector<validity::ProfileCase>& cases, const ValidityArgs& a,
                           const std::string& surface, const std::string& material) {
    nlohmann::json j;
    j["surface"] = surface;
    j["material"] = material;
    j["criteria"] = {{"peak_fraction", validity::Criteria{}.peak_fraction}, {"max_reference_stderr", a.max_reference_stderr},
                     {"tolerance", a.tolerance}, {"bin_deg", a.bin_deg}};
    j["reference"] = {{"solver", "exact-1d"},
                      {"length_um", a.length},
                      {"beam_width_um", a.beam_width},
                      {"realizations", a.realizations.value_or(0)},
                      {"target_stderr_pct", a.realizations ? 0.0 : a.target_stderr.value_or(kDefaultTargetStderrPct)},
                      {"max_realizations", a.realizations ? *a.realizations
                                                               : a.max_realizations.value_or(kDefaultMaxRealizations)},
                      {"seed", a.seed},
                      {"points_per_wavelength", a.points_per_wavelength}};
    j["notes"] = nlohmann::json::array({beam_note(a.beam_width)});
    j["cases"] = nlohmann::json::array();
    for (const auto& c : cases) {
        nlohmann::json jc;
        jc["wavelength_nm"] = c.wavelength_nm;
        jc["theta_i_deg"] = c.theta_i_deg;
        jc["polarisation"] = validity::to_string(c.polarisation);
        jc["reference_energy"] = c.reference_energy;
        jc["realizations"] = c.reference.realizations;
        jc["reference_median_rel_stderr"] = c.reference_rel_stderr;
        jc["target_reached"] = c.target_reached;
        jc["near_specular_bins_left_out"] = c.binned.near_specular_bins;
        jc["edge_rel_error"] = c.edge_rel_error;
        jc["verdict"] = verdict_json(c.verdict);
        jc["render_verdict"] = verdict_json(c.render_verdict);
        jc["not_compared"] = c.not_compared;
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
        for (const auto& m : c.models) {
            jc["models"][m.model] = model_json(m);
            jc["models"][m.model]["incoherent_per_rad"] = m.incoherent_per_rad;
        }
        j["cases"].push_back(std::move(jc));
    }
    return j;
}

// Per case the verdict over every model, and the render models' own (Kirchhoff is not a render model).
void print_summary(const std::vector<validity::ProfileCase>& cases, double beam_width_um) {
    std::printf("models: %s\n", beam_note(beam_width_um).c_str());
    for (const auto& c : cases) {
        std::printf("%s nm, theta_i %s deg, %s: %s\n", format_number(c.wavelength_nm).c_str(),
                    format_number(c.theta_i_deg).c_str(), validity::to_string(c.polarisation).c_str(),
                    c.verdict.text.c_str());
        if (c.verdict.conclusive) std::printf("  render models: %s\n", c.render_verdict.text.c_str());
        if (c.edge_rel_error >= 1e-3)
            std::printf("  profile ends: they diffract an estimated %.3g %% of the reference (median over the bins "
                        "used)\n",
                        100 * c.edge_rel_error);
        for (const std::string& why : c.not_compared) std::printf("  not compared: %s\n", why.c_str());
    }
}

void say_if_interrupted(const std::string& output, std::size_t done, std::size_t asked) {
    if (done < asked)
        std::fprintf(stderr, "surfscatter: interrupted: %s.csv holds %zu of %zu cases\n", printable_path(output).c_str(), done, asked);
}

// Exit status 2, once the outputs are written, when the reference is outside its validity in any case: one line
// saying in how many and why (the first such case's reason).
template <typename Case, typename Label>
void require_reference_valid(const std::vector<Case>& cases, Label&& label) {
    std::size_t invalid = 0;
    const Case* first = nullptr;
    for (const Case& c : cases)
        if (!c.verdict.conclusive) {
            ++invalid;
            if (!first) first = &c;
        }
    if (invalid > 0 && !interrupt_requested())
        fail("nothing can be concluded in {} of {} cases, no model is ruled out there: the reference is outside its "
             "validity ({}: {})",
             invalid, cases.size(), label(*first), first->verdict.reference_problem);
}

validity::Criteria criteria_from(const ValidityArgs& a) {
    validity::Criteria criteria;
    criteria.tolerance = a.tolerance;
    criteria.max_reference_stderr = a.max_reference_stderr;
    criteria.bin_deg = a.bin_deg;
    return criteria;
}

// OUT.csv, OUT.json and the plots of -o OUT, checked against the inputs and each other before any work.
void declare_outputs(OutputFiles& files, const ValidityArgs& a) {
    files.input(a.surface_file, "--surface-file");
    files.input(a.material, "--material");
    files.output(a.output + ".csv", "-o's CSV");
    files.output(a.output + ".json", "-o's JSON");
    files.output(a.output + "_slices.png", "-o's slices plot");
    files.output(a.output + "_error_map.png", "-o's error map");
}

// Writes them together: the plots from the JSON, by `script`.
void write_outputs(OutputFiles& files, const ValidityArgs& a, const std::string& csv, const std::string& json,
                   const char* script) {
    const std::string json_path = a.output + ".json";
    files.write(a.output + ".csv", csv);
    files.write(json_path, json);
    files.write_together({a.output + "_slices.png", a.output + "_error_map.png"},
                         [&](const std::vector<std::filesystem::path>& png) {
                             run_plot_script(script, {files.staged(json_path).string(), png[0].string(), png[1].string()});
                         });
    files.commit();
}

void print_written(const ValidityArgs& a) {
    const std::string out = printable_path(a.output);
    std::printf("wrote %s.csv, %s.json, %s_slices.png and %s_error_map.png\n", out.c_str(), out.c_str(), out.c_str(),
                out.c_str());
}

// How validity's messages name its options (the library's checks and remedies take them from here).
const reference::OptionNames kOptionNames = {.length = "--length-um",
                                             .wavelength = "--wavelengths",
                                             .points_per_wavelength = "--points-per-wavelength",
                                             .threads = "--threads",
                                             .beam_width = "--beam-width",
                                             .material = "--material",
                                             .realizations = "--realizations",
                                             .tolerance = "--tolerance",
                                             .bin_deg = "--bin-deg",
                                             .max_reference_stderr = "--max-reference-stderr",
                                             .subarea = "--subarea-um"};

void check_criteria(const ValidityArgs& a) {
    require_thread_count(a.threads, kOptionNames.threads.c_str());
    validity::require_valid_criteria(criteria_from(a), kOptionNames);
}

void run_profile_validity(const ValidityArgs& a) {
    OutputFiles files;
    declare_outputs(files, a);
    if (!a.surface.psd) fail("validity needs the surface: --psd kc|gaussian --sigma --corr-length [--gamma]");
    const auto statistics = statistics_from(a.surface);
    const auto conductor = material::Conductor::from_name(a.material);
    if (!(a.length > 0)) fail("the profiles route needs --length-um (> 0), got {}", a.length);
    require_positive(a.beam_width, "--beam-width");
    if (a.realizations && a.target_stderr)
        fail("--realizations and --target-stderr: give one (a fixed count of profiles, or profiles until the "
             "reference's standard error reaches the target)");
    if (a.realizations && a.max_realizations)
        fail("--max-realizations caps --target-stderr's profiles; --realizations {} is a fixed count", *a.realizations);
    if (a.realizations && *a.realizations < 2) fail("--realizations must be at least 2, got {}", *a.realizations);
    const double target = a.realizations ? 0.0 : a.target_stderr.value_or(kDefaultTargetStderrPct);
    if (!a.realizations && !(target > 0 && target < 100))
        fail("--target-stderr must be in (0, 100) percent, got {}", target);
    const long long cap = a.max_realizations.value_or(kDefaultMaxRealizations);
    if (!a.realizations && !(cap >= 2 && cap <= 1000000))
        fail("--max-realizations must be in [2, 1000000], got {}", cap);
    if (a.seed < 0) fail("--seed must be >= 0, got {}", a.seed);
    check_criteria(a);

    validity::ProfileStudy study;
    study.wavelengths_nm = a.wavelengths;
    study.theta_i_deg = a.theta_i;
    if (a.polarisation == "both")
        study.polarisations = {bsdf::ProfilePolarisation::s, bsdf::ProfilePolarisation::p};
    else
        study.polarisations = {bsdf::parse_profile_polarisation(a.polarisation, "--polarisation")};
    study.beam_width_um = a.beam_width;
    study.points_per_wavelength = a.points_per_wavelength;
    study.option_names = kOptionNames;
    study.statistical.length_um = a.length;
    study.statistical.realizations = static_cast<std::size_t>(a.realizations ? *a.realizations : cap);
    study.target_rel_stderr = target / 100;
    study.statistical.seed = static_cast<std::uint64_t>(a.seed);
    study.statistical.threads = a.threads;
    study.criteria = criteria_from(a);
    study.progress = true;
    install_interrupt_handler();
    const auto cases = validity::profile_validity(*statistics, conductor, study);
    const std::size_t asked = a.wavelengths.size() * a.theta_i.size() * study.polarisations.size();
    say_if_interrupted(a.output, cases.size(), asked);
    if (cases.empty()) return;

    write_outputs(files, a, csv_table(validity::table(cases), false),
                  json_report(cases, a,
                              fmt::format("{}, sigma_h {} um", statistics->cache_key(), format_number(statistics->sigma_h())),
                              conductor.name()).dump() + "\n",
                  "validity.py");
    print_summary(cases, a.beam_width);
    for (const auto& c : cases)
        if (!c.target_reached)
            std::fprintf(stderr,
                         "surfscatter: warning: %s nm, theta_i %s deg, %s: the reference's median standard error %.3g %% "
                         "did not reach the target %s %% within %zu profiles (--max-realizations): its verdict "
                         "allows for the larger uncertainty\n",
                         format_number(c.wavelength_nm).c_str(), format_number(c.theta_i_deg).c_str(),
                         validity::to_string(c.polarisation).c_str(), 100 * c.reference_rel_stderr,
                         format_number(target).c_str(), c.reference.realizations);
    print_written(a);
    require_reference_valid(cases, [](const validity::ProfileCase& c) {
        return fmt::format("{} nm, theta_i {} deg, {}", format_number(c.wavelength_nm), format_number(c.theta_i_deg),
                           validity::to_string(c.polarisation));
    });
}

nlohmann::json map_json_report(const std::vector<validity::MapCase>& cases, const ValidityArgs& a,
                               const validity::MapSurface& surface, const std::string& material) {
    nlohmann::json j;
    j["route"] = "maps";
    j["surface"] = surface.description;
    if (!a.surface_file.empty())
        j["outliers"] = {{"policy", heightmap::to_string(surface.outlier_policy)},
                         {"points", surface.outliers.count},
                         {"share", surface.outliers.share},
                         {"text", heightmap::describe(surface.outliers)}};
    j["material"] = material;
    j["criteria"] = {{"peak_fraction", validity::Criteria{}.peak_fraction}, {"max_reference_stderr", a.max_reference_stderr},
                     {"tolerance", a.tolerance}, {"bin_deg", a.bin_deg}};
    j["reference"] = {{"solver", "kirchhoff"}, {"maps", surface.maps.size()}, {"max_theta_o_deg", a.max_theta_o}};
    j["refused_models"] = surface.refused;
    j["model_notes"] = surface.notes;
    j["cases"] = nlohmann::json::array();
    for (const auto& c : cases) {
        nlohmann::json jc;
        jc["wavelength_nm"] = c.wavelength_nm;
        jc["theta_i_deg"] = c.theta_i_deg;
        jc["phi_i_deg"] = c.phi_i_deg;
        jc["polarisation"] = "unpolarised";
        jc["reference_energy"] = c.reference_energy;
        jc["reference_energy_stderr"] = c.reference_energy_stderr;
        jc["reference_subareas"] = c.subareas;
        jc["lattice_step"] = {c.lattice_step_x, c.lattice_step_y};
        jc["reference_warnings"] = c.reference_warnings;
        const auto& v = c.reference_validity;
        jc["reference_validity"] = {{"valid", v.valid}, {"k_l", v.k_l}, {"curvature_share", v.curvature_share},
                                    {"median_radius_um", v.median_radius_um}, {"shadowed_share", v.shadowed_share},
                                    {"text", v.text}};
        jc["verdict"] = verdict_json(c.verdict);
        std::vector<double> theta_deg;
        for (const double t : c.binned.theta_o_rad) theta_deg.push_back(t / kDegree);
        jc["binned"] = {{"o_x", c.binned.o_x},
                        {"o_y", c.binned.o_y},
                        {"theta_o_deg", theta_deg},
                        {"reference_per_sr", c.binned.reference},
                        {"reference_stderr_per_sr", c.binned.reference_stderr}};
        for (std::size_t m = 0; m < c.models.size(); ++m)
            jc["binned"]["models"][c.models[m].model] = c.binned.models[m];
        for (const auto& m : c.models) jc["models"][m.model] = model_json(m);
        j["cases"].push_back(std::move(jc));
    }
    return j;
}

bsdf::SurfaceOptions map_surface_options(const ValidityArgs& a) {
    bsdf::SurfaceOptions s;
    if (!a.surface_file.empty()) {
        s.psd = bsdf::PsdKind::measured;
        s.surface_file = a.surface_file;
        s.preparation = parse_preparation(a.preparation);
        return s;
    }
    if (!a.surface.psd) fail("--map-size-um synthesises maps from --psd kc|gaussian --sigma --corr-length [--gamma]");
    statistics_from(a.surface);  // checks the options, naming the bad one
    s.psd = *a.surface.psd == "kc" ? bsdf::PsdKind::kc : bsdf::PsdKind::gaussian;
    s.sigma = *a.surface.sigma;
    s.corr_length = *a.surface.corr_length;
    s.gamma = a.surface.gamma.value_or(0.0);
    if (a.corr_length_v) surface::require_surface_length(*a.corr_length_v, "--corr-length-v");
    if (a.lay_angle) require_finite(*a.lay_angle, "--lay-angle");
    s.corr_length_v = a.corr_length_v.value_or(0.0);
    s.lay_angle = a.lay_angle.value_or(0.0);
    return s;
}

void run_map_validity(const ValidityArgs& a) {
    OutputFiles files;
    declare_outputs(files, a);
    check_criteria(a);
    if (a.seed < 0) fail("--seed must be >= 0, got {}", a.seed);
    if (a.subarea) require_positive(*a.subarea, "--subarea-um");
    if (!(a.max_theta_o > 0 && a.max_theta_o < 90)) fail("--max-theta-o must be in (0, 90) degrees, got {}", a.max_theta_o);
    validity::SynthesisSettings synthesis;
    if (a.map_size) {
        synthesis.size_um = *a.map_size;
        validity::require_synthesis_counts(a.map_pixels, a.realizations.value_or(1), "--map-pixels", "--realizations");
        synthesis.pixels = static_cast<std::size_t>(a.map_pixels);
        synthesis.realizations = static_cast<std::size_t>(a.realizations.value_or(1));
        synthesis.seed = static_cast<std::uint64_t>(a.seed);
    }
    const auto conductor = material::Conductor::from_name(a.material);
    const validity::MapSurface surface = validity::map_surface(map_surface_options(a), a.material, synthesis);
    validity::MapStudy study;
    study.wavelengths_nm = a.wavelengths;
    study.theta_i_deg = a.theta_i;
    study.phi_i_deg = a.phi_i.empty() ? std::vector<double>{0.0} : a.phi_i;
    study.subarea_um = a.subarea.value_or(0.0);
    study.max_theta_o_deg = a.max_theta_o;
    study.criteria = criteria_from(a);
    study.threads = a.threads;
    study.option_names = kOptionNames;
    if (!a.map_size) study.option_names.realizations.clear();  // a measured map: one realization
    study.progress = true;
    validity::check_map_study(surface, study);  // a refusal before the notes is one line
    for (const std::string& note : surface.notes) print_note("", note);
    for (const std::string& why : surface.refused)
        std::fprintf(stderr, "surfscatter: not compared: %s\n", why.c_str());
    install_interrupt_handler();
    const auto cases = validity::map_validity(surface, conductor, study);
    const std::size_t asked = a.wavelengths.size() * a.theta_i.size() * study.phi_i_deg.size();
    say_if_interrupted(a.output, cases.size(), asked);
    if (cases.empty()) return;

    write_outputs(files, a, csv_table(validity::table(cases), true),
                  map_json_report(cases, a, surface, conductor.name()).dump() + "\n", "validity_map.py");
    for (const auto& c : cases) {
        for (const std::string& w : c.reference_warnings)
            std::fprintf(stderr, "surfscatter: warning: %s nm, theta_i %s deg: %s\n",
                         format_number(c.wavelength_nm).c_str(), format_number(c.theta_i_deg).c_str(), w.c_str());
        std::printf("%s nm, theta_i %s deg, phi_i %s deg: %s\n", format_number(c.wavelength_nm).c_str(),
                    format_number(c.theta_i_deg).c_str(), format_number(c.phi_i_deg).c_str(), c.verdict.text.c_str());
    }
    print_written(a);
    validity::require_outliers_not_dominant(surface);
    require_reference_valid(cases, [](const validity::MapCase& c) {
        return fmt::format("{} nm, theta_i {} deg, phi_i {} deg", format_number(c.wavelength_nm),
                           format_number(c.theta_i_deg), format_number(c.phi_i_deg));
    });
}

const Command command("validity", [](CLI::App& app) {
    auto a = std::make_shared<ValidityArgs>();
    auto* sub = app.add_subcommand(
        "validity", "Which model to trust: the 1-D GHS, SSA, Kirchhoff, GGX and two_scale forms against the exact 1-D "
                    "solution averaged over random profiles, per wavelength, incidence and polarisation "
                    "(--length-um); or "
                    "every 2-D model against the Kirchhoff BRDF of a height map (--surface-file) or of maps "
                    "synthesised from the statistics (--map-size-um), with Kirchhoff's own validity "
                    "(docs/VALIDITY.md)");
    a->surface.add_to(sub, "kc or gaussian PSD of the surface the random profiles are cuts through (profiles route) "
                           "or the maps are synthesised from (map route)");
    sub->add_option("--material", a->material,
                    "perfect, a built-in metal (Ag, Au, Al, Cu, ...) or a .yml/.csv refractive index file")
        ->required();
    add_number_list(sub, "--wavelengths", a->wavelengths, "wavelengths in nm, comma-separated")->required();
    add_number_list(sub, "--theta-i", a->theta_i, "angles of incidence in degrees, comma-separated")->required();
    sub->add_option("--polarisation", a->polarisation, "s | p | both (default)")
        ->check(CLI::IsMember({"s", "p", "both"}));
    sub->add_option("--length-um", a->length,
                    "profiles route: length of each random profile (um), centred on x = 0");
    sub->add_option("--beam-width", a->beam_width, "profiles route: Thorsos taper width g along x in um");
    sub->add_option("--realizations", a->realizations,
                    "a fixed number of random profiles per case (profiles route, >= 2; instead of --target-stderr), "
                    "or maps synthesised (map route, default 1)");
    sub->add_option("--target-stderr", a->target_stderr,
                    "profiles route: profiles run until the reference's median relative standard error over the "
                    "bins used reaches this many percent (default 2)");
    sub->add_option("--max-realizations", a->max_realizations,
                    "profiles route: the most profiles --target-stderr runs per case (default 1000); short of the "
                    "target, a warning says so");
    sub->add_option("--seed", a->seed, "seed of the first profile or map; number r uses seed + r (default 1)");
    sub->add_option("--surface-file", a->surface_file,
                    "map route: a measured height map (any format `surface info` reads) as the surface");
    add_preparation_options(sub, a->preparation, "map route: --surface-file");
    sub->add_option("--map-size-um", a->map_size, "map route: side of the square maps synthesised from --psd (um)");
    sub->add_option("--map-pixels", a->map_pixels, "map route: pixels per side of the synthesised maps (default 256)");
    sub->add_option("--corr-length-v", a->corr_length_v,
                    "map route: correlation length across the lay (um): elliptical statistics");
    sub->add_option("--lay-angle", a->lay_angle, "map route: lay direction from x towards y, degrees (default 0)");
    add_number_list(sub, "--phi-i", a->phi_i, "map route: incidence azimuths in degrees, comma-separated (default 0)");
    sub->add_option("--subarea-um", a->subarea,
                    "map route: Kirchhoff sub-area side (um; default a quarter of the map's shorter side)");
    sub->add_option("--max-theta-o", a->max_theta_o, "map route: largest theta_o compared, degrees (default 80)");
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
    sub->callback([a, sub] {
        const std::string& mode = validity_mode(*a);
        require_applicable_options(*sub, mode, kValidityScopes);
        if (mode == kProfiles)
            run_profile_validity(*a);
        else
            run_map_validity(*a);
    });
});

}  // namespace

}  // namespace surfscatter::cli
