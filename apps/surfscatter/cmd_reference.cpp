// surfscatter reference exact-1d: the rigorous scattering of a tapered beam by a 1-D profile (docs/REFERENCE.md),
// written as CSV theta_o_deg,intensity_per_rad; with --psd, averaged over random profiles (coherent and incoherent
// parts and their standard errors in further columns).
// surfscatter reference kirchhoff: the Kirchhoff BRDF of a height map on its sub-areas' direction lattice, CSV
// theta_o_deg,phi_o_deg,brdf_per_sr,standard_error_per_sr,coherent_per_sr, with a PNG (docs/REFERENCE.md).
// surfscatter reference models-1d: the models' 1-D forms on exact-1d's grid (docs/REFERENCE.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>
#include <optional>
#include <utility>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "option_scope.hpp"
#include "preparation_options.hpp"
#include "profile_surface_options.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/reference/profile.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::cli {

namespace {

struct Exact1dArgs {
    std::string profile, material, polarisation, output;
    double wavelength = 0, theta_i = 0, beam_width = 0, points_per_wavelength = 10;
    // Statistical mode.
    SurfaceArgs surface;
    std::optional<double> length;
    long long realizations = 0, seed = 1;
    int threads = 0;
};

// --material, --wavelength, --theta-i and --polarisation, as exact-1d and models-1d spell them.
void add_incidence_options(CLI::App* sub, std::string& material, double& wavelength, double& theta_i,
                           std::string& polarisation) {
    sub->add_option("--material", material,
                    "perfect, a built-in metal (Ag, Au, Al, Cu, ...) or a .yml/.csv refractive index file")
        ->required();
    sub->add_option("--wavelength", wavelength, "wavelength in nm")->required();
    sub->add_option("--theta-i", theta_i, "angle of incidence in degrees, light arriving from negative x")->required();
    sub->add_option("--polarisation", polarisation, "s (TE, E along y) or p (TM, H along y)")
        ->required()
        ->check(CLI::IsMember({"s", "p"}));
}

std::string statistics_csv(const reference::StatisticalResult& r) {
    std::string out = "theta_o_deg,intensity_per_rad,coherent_per_rad,coherent_stderr_per_rad,incoherent_per_rad,"
                      "incoherent_stderr_per_rad\n";
    for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j)
        out += fmt::format("{},{},{},{},{},{}\n", format_number(r.theta_o_rad[j] / kDegree),
                           format_number(r.intensity[j]), format_number(r.coherent[j]),
                           format_number(r.coherent_stderr[j]), format_number(r.incoherent[j]),
                           format_number(r.incoherent_stderr[j]));
    return out;
}

std::string far_field_csv(const reference::FarField& far_field) {
    std::string out = "theta_o_deg,intensity_per_rad\n";
    const auto intensity = far_field.intensity_per_rad();
    for (std::size_t j = 0; j < intensity.size(); ++j)
        out += fmt::format("{},{}\n", format_number(far_field.theta_o_rad[j] / kDegree), format_number(intensity[j]));
    return out;
}

// --theta-i in [0, 90) degrees and --wavelength > 0, as every reference command takes them.
void require_incidence(double theta_i, double wavelength) {
    require_finite(theta_i, "--theta-i");
    if (theta_i < 0 || theta_i >= 90) fail("--theta-i must be in [0, 90) degrees, got {}", theta_i);
    require_positive(wavelength, "--wavelength");
}

// exact-1d's two modes and the options only the statistical one takes.
const std::string kOneProfile = "one profile (--profile)", kRandomProfiles = "the statistical mode (--psd)";
const std::vector<OptionScope> kExact1dScopes = {
    {"--sigma", {kRandomProfiles}},       {"--corr-length", {kRandomProfiles}}, {"--gamma", {kRandomProfiles}},
    {"--length-um", {kRandomProfiles}},   {"--realizations", {kRandomProfiles}}, {"--seed", {kRandomProfiles}},
    {"--threads", {kRandomProfiles}},
};

void run_exact_1d(const Exact1dArgs& a, const CLI::App& sub) {
    require_applicable_options(sub, a.surface.psd ? kRandomProfiles : kOneProfile, kExact1dScopes);
    OutputFiles files;
    files.input(a.profile, "--profile");
    files.input(a.material, "--material");
    files.output(a.output, "-o");
    require_incidence(a.theta_i, a.wavelength);
    require_positive(a.beam_width, "--beam-width");
    const auto conductor = material::Conductor::from_name(a.material);
    reference::Exact1dOptions options;
    options.lambda_nm = a.wavelength;
    options.theta_i_rad = a.theta_i * kDegree;
    options.polarisation = a.polarisation == "s" ? reference::Polarisation::s : reference::Polarisation::p;
    options.beam_width_um = a.beam_width;
    options.points_per_wavelength = a.points_per_wavelength;
    options.option_names = {.length = a.surface.psd ? "--length-um" : "profile in --profile",
                            .wavelength = "--wavelength",
                            .points_per_wavelength = "--points-per-wavelength",
                            .threads = "--threads",
                            .beam_width = "--beam-width",
                            .material = "--material",
                            .realizations = "--realizations"};
    if (!a.surface.psd) {
        if (a.profile.empty()) fail("give --profile FILE.csv or the statistical mode --psd kc|gaussian");
        const reference::Profile profile = reference::read_profile_csv(a.profile);
        files.write(a.output, far_field_csv(reference::solve_exact_1d(profile, conductor, options)));
        files.commit();
        return;
    }
    if (!a.profile.empty()) fail("--profile and --psd exclude each other: one profile or random ones");
    const auto statistics = statistics_from(a.surface);
    if (!a.length) fail("--psd needs --length-um (the random profiles' length)");
    if (a.realizations < 2) fail("--realizations must be at least 2, got {}", a.realizations);
    if (a.seed < 0) fail("--seed must be >= 0, got {}", a.seed);
    require_thread_count(a.threads, "--threads");
    reference::StatisticalOptions st;
    st.length_um = *a.length;
    st.realizations = static_cast<std::size_t>(a.realizations);
    st.seed = static_cast<std::uint64_t>(a.seed);
    st.threads = a.threads;
    st.progress = true;
    install_interrupt_handler();
    const auto result = reference::solve_exact_1d_statistics(*statistics, conductor, options, st);
    if (result.realizations < st.realizations)
        std::fprintf(stderr, "surfscatter: interrupted: %s holds %zu of %zu realizations\n", printable_path(a.output).c_str(),
                     result.realizations, st.realizations);
    if (result.realizations == 0) return;
    files.write(a.output, statistics_csv(result));
    files.commit();
}

struct KirchhoffArgs {
    std::string surface_file, material, output, plot;
    PreparationArgs preparation;
    double wavelength = 0, theta_i = 0, phi_i = 0, max_theta_o = 85;
    std::optional<double> subarea;
    int threads = 0;
};

std::string kirchhoff_csv(const reference::KirchhoffResult& r) {
    std::string out = "theta_o_deg,phi_o_deg,brdf_per_sr,standard_error_per_sr,coherent_per_sr\n";
    for (std::size_t d = 0; d < r.brdf.size(); ++d) {
        const double sin_o = std::hypot(r.o_x[d], r.o_y[d]);
        double phi = std::atan2(r.o_y[d], r.o_x[d]) / kDegree;
        if (phi < 0) phi += 360;
        out += fmt::format("{},{},{},{},{}\n", format_number(std::asin(std::min(1.0, sin_o)) / kDegree),
                           format_number(phi), format_number(r.brdf[d]), format_number(r.standard_error[d]),
                           format_number(r.coherent[d]));
    }
    return out;
}

void run_kirchhoff(const KirchhoffArgs& a) {
    OutputFiles files;
    files.input(a.surface_file, "--surface");
    files.input(a.material, "--material");
    files.output(a.output, "-o");
    if (!a.plot.empty()) files.output(a.plot, "--plot");
    require_incidence(a.theta_i, a.wavelength);
    require_finite(a.phi_i, "--phi-i");
    require_finite(a.max_theta_o, "--max-theta-o");
    if (a.max_theta_o <= 0 || a.max_theta_o >= 90)
        fail("--max-theta-o must be in (0, 90) degrees, got {}", a.max_theta_o);
    if (a.subarea) require_positive(*a.subarea, "--subarea-um");
    require_thread_count(a.threads, "--threads");
    parse_preparation(a.preparation);  // its errors before the material's
    const auto conductor = material::Conductor::from_name(a.material);
    const heightmap::PreparedMap prepared = read_prepared_map(a.surface_file, {}, {}, a.preparation);
    const heightmap::HeightMap& map = prepared.map;
    for (const std::string& warning : map.source.warnings)
        std::fprintf(stderr, "surfscatter: warning: %s: %s\n", printable_path(a.surface_file).c_str(), warning.c_str());
    reference::KirchhoffOptions o;
    o.lambda_nm = a.wavelength;
    o.theta_i_rad = a.theta_i * kDegree;
    o.phi_i_rad = a.phi_i * kDegree;
    // Default: a quarter of the shorter side, 16 sub-areas.
    o.subarea_um = a.subarea ? *a.subarea : 0.25 * std::min(map.width(), map.height());
    o.max_theta_o_rad = a.max_theta_o * kDegree;
    o.threads = a.threads;
    o.option_names = {.wavelength = "--wavelength", .threads = "--threads", .subarea = "--subarea-um"};
    o.progress = true;
    install_interrupt_handler();
    const auto r = reference::kirchhoff_brdf(map, conductor, o);
    for (const std::string& warning : r.warnings) std::fprintf(stderr, "surfscatter: warning: %s\n", warning.c_str());
    if (r.subareas_done < r.subareas)
        std::fprintf(stderr, "surfscatter: interrupted: %s holds %zu of %zu sub-areas\n", printable_path(a.output).c_str(),
                     r.subareas_done, r.subareas);
    if (r.subareas_done == 0) return;
    files.write(a.output, kirchhoff_csv(r));
    if (!a.plot.empty())
        files.write_with(a.plot, [&](const std::filesystem::path& png) {
            run_plot_script("kirchhoff_map.py", {files.staged(a.output).string(), png.string(), format_number(a.theta_i),
                                                 format_number(a.phi_i), format_number(r.step_x), format_number(r.step_y),
                                                 fmt::format("{} nm, {}", format_number(a.wavelength), a.material)});
        });
    files.commit();
    print_note("", fmt::format("{}: {}", printable_path(a.surface_file), heightmap::describe(prepared)));
    std::printf("subareas = %zu\nsubarea_px = %zu x %zu\n", r.subareas_done, r.subarea_nx, r.subarea_ny);
    std::printf("lattice_step = %s x %s\n", format_number(r.step_x).c_str(), format_number(r.step_y).c_str());
    std::printf("qz_bands = %zu\nffts_per_subarea = %zu\n", r.band_count, r.fft_count);
    std::printf("albedo = %s\nalbedo_standard_error = %s\ncoherent_albedo = %s\naliased_fraction = %s\n",
                format_number(r.albedo).c_str(), format_number(r.albedo_standard_error).c_str(),
                format_number(r.coherent_albedo).c_str(), format_number(r.aliased_fraction).c_str());
}

void add_kirchhoff(CLI::App* reference_cmd) {
    auto a = std::make_shared<KirchhoffArgs>();
    auto* sub = reference_cmd->add_subcommand(
        "kirchhoff", "Kirchhoff (tangent-plane) BRDF of a height map by FFT over Hann-windowed sub-areas: CSV "
                     "theta_o_deg,phi_o_deg,brdf_per_sr,standard_error_per_sr,coherent_per_sr");
    sub->add_option("--surface", a->surface_file, "height map (any format `surface info` reads)")->required();
    add_preparation_options(sub, a->preparation);
    sub->add_option("--material", a->material,
                    "perfect, a built-in metal (Ag, Au, Al, Cu, ...) or a .yml/.csv refractive index file")
        ->required();
    sub->add_option("--wavelength", a->wavelength, "wavelength in nm")->required();
    sub->add_option("--theta-i", a->theta_i, "angle of incidence in degrees")->required();
    sub->add_option("--phi-i", a->phi_i, "azimuth of incidence in the map's frame (x = 0 deg), degrees (default 0)");
    sub->add_option("--subarea-um", a->subarea, "side of the square sub-areas averaged over (um; default a quarter of "
                                                "the map's shorter side): angular resolution lambda / side");
    sub->add_option("--max-theta-o", a->max_theta_o, "largest theta_o written, degrees (default 85)");
    sub->add_option("--threads", a->threads, "sub-areas evaluated at once, 0 = all cores (default)");
    sub->add_option("-o", a->output, "output CSV")->required();
    sub->add_option("--plot", a->plot, "PNG: the BRDF over the direction cosines and the in-plane slice");
    sub->callback([a] { run_kirchhoff(*a); });
}

// surfscatter reference models-1d: the 1-D forms of the models (bsdf/profile_lobes.hpp) on exact-1d's theta_o grid.
struct Models1dArgs {
    SurfaceArgs surface;
    std::string material, polarisation, output, model = "all", fresnel = "incident", ssa_form = "energy";
    double wavelength = 0, theta_i = 0;
    bool no_renormalization = false;
};

std::vector<bsdf::ProfileModel> chosen_models(const Models1dArgs& a, const CLI::App& sub) {
    const std::vector<bsdf::ProfileModel> models =
        a.model == "all" ? std::vector{bsdf::ProfileModel::ghs, bsdf::ProfileModel::ghs_ssa, bsdf::ProfileModel::kirchhoff}
                         : std::vector{bsdf::parse_profile_model(a.model, "--model")};
    // An option none of the chosen models uses is an error, never ignored (as in brdf).
    for (const auto& [flag, option] : {std::pair{"--fresnel", "fresnel"}, std::pair{"--ssa-form", "ssa_form"},
                                       std::pair{"--no-renormalization", "renormalization"}}) {
        const auto why = bsdf::inapplicable_profile_option(models, option);
        if (sub.count(flag) > 0 && !why.empty()) fail("{} is {}", flag, why);
    }
    return models;
}

void run_models_1d(const Models1dArgs& a, const CLI::App& sub) {
    const std::filesystem::path out(a.output);
    const auto json_path = std::filesystem::path(out).replace_extension(".json");
    const auto png_path = std::filesystem::path(out).replace_extension(".png");
    OutputFiles files;
    files.input(a.material, "--material");
    files.output(out, "-o");
    files.output(json_path, "the JSON beside -o");
    files.output(png_path, "the PNG beside -o");
    require_incidence(a.theta_i, a.wavelength);
    if (!a.surface.psd) fail("models-1d needs the surface: --psd kc|gaussian --sigma --corr-length [--gamma]");
    const auto statistics = statistics_from(a.surface);
    const auto conductor = material::Conductor::from_name(a.material);
    const auto models = chosen_models(a, sub);
    bsdf::ProfileModelOptions options;
    options.fresnel = bsdf::parse_fresnel(a.fresnel, "--fresnel");
    options.ssa_form = bsdf::parse_ssa_form(a.ssa_form, "--ssa-form");
    options.renormalization = !a.no_renormalization;
    const auto polarisation = bsdf::parse_profile_polarisation(a.polarisation, "--polarisation");
    const auto theta_o = bsdf::uniform_theta_grid(reference::kFarFieldSteps);
    bsdf::require_profile_wavelength(a.wavelength, "--wavelength");

    std::string header = "theta_o_deg";
    std::vector<bsdf::ProfileLobe> lobes;
    nlohmann::json json;
    json["theta_i_deg"] = a.theta_i;
    json["wavelength_nm"] = a.wavelength;
    json["polarisation"] = a.polarisation;
    json["material"] = conductor.name();
    json["surface"] = statistics->cache_key();
    json["sigma_h_um"] = statistics->sigma_h();
    for (const auto model : models) {
        options.model = model;
        lobes.push_back(bsdf::profile_lobe(*statistics, conductor, a.wavelength, a.theta_i * kDegree, polarisation,
                                           options, theta_o));
        const auto name = bsdf::to_string(model);
        header += fmt::format(",{}_per_rad", name);
        json["models"][name] = {{"coherent", lobes.back().coherent},
                                {"sigma_um", lobes.back().sigma_um},
                                {"normalization", lobes.back().normalization}};
        std::printf("%s: coherent fraction %s (sigma %s um, normalisation %s)\n", name.c_str(),
                    format_number(lobes.back().coherent).c_str(), format_number(lobes.back().sigma_um).c_str(),
                    format_number(lobes.back().normalization).c_str());
    }
    std::string csv = header + "\n";
    for (std::size_t j = 0; j < theta_o.size(); ++j) {
        csv += format_number(theta_o[j] / kDegree);
        for (const auto& lobe : lobes) csv += fmt::format(",{}", format_number(lobe.intensity_per_rad[j]));
        csv += "\n";
    }
    files.write(out, csv);
    files.write(json_path, json.dump(2) + "\n");
    files.write_with(png_path, [&](const std::filesystem::path& png) {
        run_plot_script("models_1d.py",
                        {files.staged(out).string(), files.staged(json_path).string(), png.string(),
                         fmt::format("{}, {} nm, theta_i {} deg, {}", conductor.name(), format_number(a.wavelength),
                                     format_number(a.theta_i), a.polarisation)});
    });
    files.commit();
    std::printf("wrote %s, %s and %s\n", printable_path(out).c_str(), printable_path(json_path).c_str(), printable_path(png_path).c_str());
}

void add_models_1d(CLI::App* cmd) {
    auto a = std::make_shared<Models1dArgs>();
    auto* sub = cmd->add_subcommand(
        "models-1d", "The 1-D forms of GHS, SSA and Kirchhoff for a profile with the statistical mode's surface, on "
                     "exact-1d's theta_o grid: CSV theta_o_deg,<model>_per_rad (incoherent part), JSON with the "
                     "coherent fractions, PNG plot");
    a->surface.add_to(sub, "kc or gaussian PSD of the isotropic surface the profile is a cut through");
    add_incidence_options(sub, a->material, a->wavelength, a->theta_i, a->polarisation);
    sub->add_option("--model", a->model, "ghs | ghs_ssa | kirchhoff | all (default)");
    sub->add_option("--fresnel", a->fresnel, "ghs, ghs_ssa: incident (|r(theta_i)|^2, default) | half | rr");
    sub->add_option("--ssa-form", a->ssa_form, "ghs_ssa: energy (default) | strict");
    sub->add_flag("--no-renormalization", a->no_renormalization, "ghs: sigma_h instead of sigma_rel and K = 1");
    sub->add_option("-o", a->output, "output CSV (the JSON and PNG are written beside it)")->required();
    sub->callback([a, sub] { run_models_1d(*a, *sub); });
}

const Command command("reference", [](CLI::App& app) {
    auto* cmd = app.add_subcommand("reference", "Rigorous scattering solutions the models are checked against");
    cmd->require_subcommand(1);
    auto a = std::make_shared<Exact1dArgs>();
    auto* sub = cmd->add_subcommand(
        "exact-1d", "Boundary-integral solution for a 1-D profile z = h(x) under a Thorsos-tapered beam: CSV "
                    "theta_o_deg,intensity_per_rad (scattered power per radian over the incident power)");
    sub->add_option("--profile", a->profile, "profile CSV with header x_um,h_um, uniformly spaced, beam centred at x = 0");
    add_incidence_options(sub, a->material, a->wavelength, a->theta_i, a->polarisation);
    sub->add_option("--beam-width", a->beam_width, "Thorsos taper width g along x in um")->required();
    sub->add_option("--points-per-wavelength", a->points_per_wavelength,
                    "solver nodes per wavelength along x, 4..1000 (default 10)");
    sub->add_option("-o", a->output, "output CSV")->required();
    a->surface.add_to(sub, "statistical mode: random profiles with a kc or gaussian PSD (a cut through the isotropic "
                           "surface)");
    sub->add_option("--length-um", a->length, "length of each random profile (um), centred on x = 0");
    sub->add_option("--realizations", a->realizations, "number of random profiles (>= 2)");
    sub->add_option("--seed", a->seed, "seed of the first profile; profile r uses seed + r (default 1)");
    sub->add_option("--threads", a->threads, "realizations solved at once, 0 = all cores (default)");
    sub->callback([a, sub] { run_exact_1d(*a, *sub); });
    add_kirchhoff(cmd);
    add_models_1d(cmd);
});

}  // namespace

}  // namespace surfscatter::cli
