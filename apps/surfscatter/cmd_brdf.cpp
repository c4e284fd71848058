// surfscatter brdf eval | albedo | sample | slice | export: the scattering models of docs/MODELS.md from the command line.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <utility>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "list_options.hpp"
#include "preparation_options.hpp"
#include "profile_route.hpp"
#include "surfscatter/bsdf/albedo.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/measured_band.hpp"
#include "surfscatter/bsdf/rgl_export.hpp"
#include "surfscatter/bsdf/slice.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/resources.hpp"

namespace surfscatter::cli {

namespace {

// Options as typed; turned into bsdf::ModelOptions (same names, snake_case) by model_options().
struct BrdfArgs {
    std::string model = "ghs", method = "exact", truncation = "three_sigma", fresnel = "incident";
    std::string ssa_form = "energy", alpha_from, macro_ndf = "ggx", material;  // alpha_from, material: not given
    double epsilon = 1e-6, alpha = 0, smoothing = 0, cutoff_wavelengths = 100;
    bool no_renormalization = false;
    std::string psd, psd_fit, surface_file;  // psd_fit: not given
    PreparationArgs preparation;
    std::string measured_spectrum = "2d";
    double sigma = 0, corr_length = 0, gamma = 0, corr_length_v = 0, lay_angle = 0;
    // The --surface map, read and prepared when first needed and shared by every model of the command.
    mutable std::shared_ptr<const heightmap::PreparedMap> prepared;
    // A --surface profile (profile_route.hpp), read when first needed (`profile_checked` once looked for), and its
    // KC (--psd file) or its measured statistics (--psd measured, the default), each made when first needed.
    mutable std::optional<heightmap::LineScan> profile_scan;
    mutable std::optional<ProfileSurface> profile;
    mutable std::shared_ptr<const surface::ProfileStatistics> profile_measured;
    mutable bool profile_checked = false;
    double wavelength = 0, phi_i = 0;
    std::vector<double> theta_i;
    // eval
    std::vector<double> theta_o, phi_o;
    // sample
    long long count = 1000;
    long long seed = 1;
    // export
    std::string format, output;
    bsdf::RglExportOptions export_options;
    double tolerance_percent = 2;
    double specular_lobe_deg = 0;  // > 0: the delta part carried in the file as a lobe of this width
    // slice
    std::vector<std::string> models;
    std::string plot, csv;
    // Model options given on the command line, as named in ModelOptions ("smoothing", "surface_file").
    std::vector<std::string> given;
};

// The long names of the options given to `cmd`, spelt as in ModelOptions (--no-renormalization: renormalization).
std::vector<std::string> given_options(const CLI::App* cmd) {
    std::vector<std::string> names;
    for (const CLI::Option* option : cmd->get_options()) {
        if (option->count() == 0 || option->get_lnames().empty()) continue;
        std::string name = option->get_lnames().front();
        std::replace(name.begin(), name.end(), '-', '_');
        if (name == "no_renormalization") name = "renormalization";
        if (name == "surface") name = "surface_file";
        names.push_back(name);
    }
    return names;
}

// The option as the user typed it, from its ModelOptions name.
std::string flag_name(std::string name) {
    if (name == "renormalization") return "--no-renormalization";
    if (name == "surface_file") return "--surface";
    std::replace(name.begin(), name.end(), '_', '-');
    return "--" + name;
}

// An option given for a model that does not use it is an error, never silently ignored.
void check_given_options_apply(const BrdfArgs& a, const std::vector<bsdf::ModelOptions>& models,
                               const std::vector<std::string>& model_names) {
    for (const std::string& name : a.given) {
        // A --surface profile stands for the KC fitted to it or its own spectrum (model_options): its file, --psd and
        // --form are used (--psd-fit by the KC's route, which refuses elliptical).
        if (a.profile_scan && (name == "surface_file" || name == "psd" || name == "form" || (name == "psd_fit" && a.profile)))
            continue;
        std::string why;
        for (const bsdf::ModelOptions& o : models) {
            why = bsdf::inapplicable_option(o, name);
            if (why.empty()) break;
        }
        if (!why.empty())
            fail("{} does not apply to {} {}: {}", flag_name(name), model_names.size() > 1 ? "--models" : "--model",
                 fmt::join(model_names, ","), why);
    }
}

void require_theta(double t, const char* what) {
    require_finite(t, what);
    if (t < 0 || t >= 90) fail("{} must be in [0, 90) degrees, got {}", what, t);
}

// Whether the option `name` (as in ModelOptions) was given on the command line.
bool given(const BrdfArgs& a, const char* name) { return std::count(a.given.begin(), a.given.end(), name) > 0; }

// `spec` is a model name, optionally with the surface statistics to use after a colon (brdf slice --models
// ghs:file,ghs:measured overlays the KC-fit and measured-PSD versions of one model on the same --surface).
bsdf::ModelOptions model_options(const BrdfArgs& a, const std::string& spec) {
    const std::size_t colon = spec.find(':');
    const bool kc_given = given(a, "sigma") || given(a, "corr_length") || given(a, "gamma");
    // KC parameters without --psd (and without --surface) mean --psd kc, as in scenes and Python.
    const std::string psd = colon != std::string::npos ? spec.substr(colon + 1)
                            : !a.psd.empty() || !a.surface_file.empty() || !kc_given ? a.psd
                                                                                     : std::string("kc");
    bsdf::ModelOptions o;
    o.model = bsdf::parse_model(spec.substr(0, colon), a.models.empty() ? "--model" : "--models");
    const std::string model = bsdf::to_string(o.model);
    o.method = bsdf::parse_method(a.method, "--method");
    o.truncation = bsdf::parse_truncation(a.truncation, "--truncation");
    o.epsilon = a.epsilon;
    o.fresnel = bsdf::parse_fresnel(a.fresnel, "--fresnel");
    o.renormalization = !a.no_renormalization;
    o.ssa_form = bsdf::parse_ssa_form(a.ssa_form, "--ssa-form");
    o.alpha = a.alpha;
    if (!a.alpha_from.empty()) o.alpha_from = bsdf::parse_alpha_from(a.alpha_from, "--alpha-from");
    bsdf::imply_alpha_from(o, given(a, "alpha"), !a.alpha_from.empty());
    o.smoothing = a.smoothing;
    o.cutoff_wavelengths = a.cutoff_wavelengths;
    o.macro_ndf = bsdf::parse_macro_ndf(a.macro_ndf, "--macro-ndf");
    o.material = a.material;
    const bool needs_surface = o.model != bsdf::ModelKind::ggx || o.alpha_from != bsdf::AlphaFrom::none;
    const bool from_map = psd.empty() || psd == "file" || psd == "measured";
    if (!a.surface_file.empty() && from_map && !a.profile_checked) {
        a.profile_checked = true;
        a.profile_scan = read_profile(a.surface_file, a.preparation);
        if (a.profile_scan)
            std::fprintf(stderr, "surfscatter: brdf: %s\n",
                         heightmap::describe_profile(*a.profile_scan, profile_form(a.preparation)).c_str());
    }
    if (a.profile_scan && psd == "file") {
        // --psd file: the KC fitted to the profile's 1-D PSD as the isotropic surface's.
        if (!a.psd_fit.empty() && bsdf::parse_psd_fit(a.psd_fit, "--psd-fit") == bsdf::PsdFit::elliptical)
            fail("--psd-fit elliptical: {} is a profile, which holds no lay direction", a.surface_file);
        if (!a.profile) {
            a.profile = profile_surface(*a.profile_scan, profile_form(a.preparation));
            print_note("brdf", a.profile->note);
        }
        o.surface.psd = bsdf::PsdKind::kc;
        o.surface.sigma = a.profile->fit.kc.sigma_h_um;
        o.surface.corr_length = a.profile->fit.kc.corr_length_um;
        o.surface.gamma = a.profile->fit.kc.gamma;
    } else if (a.profile_scan && from_map) {
        // --psd measured, a profile's default: its own spectrum as an isotropic surface's (profile_route.hpp).
        if (!a.profile_measured)
            a.profile_measured =
                std::make_shared<const surface::ProfileStatistics>(*a.profile_scan, profile_form(a.preparation));
        o.surface.psd = bsdf::PsdKind::measured;
        o.surface.surface_file = a.surface_file;
        o.surface.measured_profile = a.profile_measured;
        o.surface.measured_spectrum = bsdf::parse_measured_spectrum(a.measured_spectrum, "--measured-spectrum");
    } else if (!a.surface_file.empty() && from_map) {
        o.surface.psd = psd.empty() ? bsdf::PsdKind::file : bsdf::parse_psd(psd, "--psd");
        o.surface.surface_file = a.surface_file;
        o.surface.preparation = parse_preparation(a.preparation);
        // Parsed for every map model, used by psd file only (slice --models ghs:file,ghs:measured).
        const bsdf::PsdFit fit = a.psd_fit.empty() ? bsdf::PsdFit::isotropic : bsdf::parse_psd_fit(a.psd_fit, "--psd-fit");
        if (o.surface.psd == bsdf::PsdKind::file) o.surface.psd_fit = fit;
        o.surface.measured_spectrum = bsdf::parse_measured_spectrum(a.measured_spectrum, "--measured-spectrum");
        if (!a.prepared) {
            bsdf::load_height_map(o.surface);
            a.prepared = o.surface.prepared;
        }
        o.surface.prepared = a.prepared;
    } else if (!a.surface_file.empty() && a.psd == psd) {
        fail("--surface takes --psd file (KC fitted to the map, the default) or measured (its own PSD), got --psd {}", psd);
    } else if (!psd.empty()) {
        o.surface.psd = bsdf::parse_psd(psd, "--psd");
        if (o.surface.psd == bsdf::PsdKind::file || o.surface.psd == bsdf::PsdKind::measured)
            fail("--psd {} needs --surface MAP", psd);
        if (o.surface.psd == bsdf::PsdKind::gaussian && a.gamma != 0) fail("--gamma applies to --psd kc only");
        if (o.surface.psd == bsdf::PsdKind::kc && a.gamma == 0 && a.psd.empty())
            fail("--sigma and --corr-length without --psd mean --psd kc, which needs --gamma (or give --psd gaussian)");
        if (o.surface.psd == bsdf::PsdKind::kc && a.gamma == 0) fail("--psd kc needs --gamma");
        o.surface.sigma = a.sigma;
        o.surface.corr_length = a.corr_length;
        o.surface.gamma = a.gamma;
        o.surface.corr_length_v = a.corr_length_v;
        o.surface.lay_angle = a.lay_angle;
    } else if (needs_surface) {
        fail("missing surface for --model {}: give --sigma S --corr-length L --gamma G (KC), "
             "--psd gaussian --sigma S --corr-length l, or --surface MAP{}", model,
             o.model == bsdf::ModelKind::ggx ? ", or --alpha A for a given roughness" : "");
    }
    // No silent perfect mirror (a user comparing with gold got 74.2 instead of 55.4 1/sr): the metal is asked for.
    if (a.material.empty())
        fail("--material is required: a built-in metal (Au, Ag, Al, Cu, ...), a refractive-index file, or "
             "--material perfect for a perfect conductor (R = 1)");
    return o;
}

// The model of `options`, its notes (e.g. how a measured PSD is extrapolated) on stderr, each once per run.
std::unique_ptr<bsdf::Bsdf> build_model(const bsdf::ModelOptions& options) {
    static std::vector<std::string> printed;
    std::vector<std::string> notes;
    auto model = bsdf::make_bsdf(options, &notes);
    // The --surface map is described once the model is built from it: a map the model refuses gives the error alone.
    static const heightmap::PreparedMap* described = nullptr;
    if (options.surface.prepared && options.surface.prepared.get() != described) {
        described = options.surface.prepared.get();
        std::fprintf(stderr, "surfscatter: brdf: %s\n", heightmap::describe(described->map).c_str());
    }
    for (const std::string& note : notes)
        if (std::find(printed.begin(), printed.end(), note) == printed.end()) {
            print_note("brdf", note);
            printed.push_back(note);
        }
    return model;
}

void check_common(const BrdfArgs& a) {
    require_finite(a.wavelength, "--wavelength");
    if (!(a.wavelength > 0)) fail("--wavelength must be > 0 nm, got {}", a.wavelength);
    if (a.theta_i.empty()) fail("--theta-i is required");
    for (double t : a.theta_i) require_theta(t, "--theta-i");
    require_finite(a.phi_i, "--phi-i");
}

Vec3 incident(double theta_deg, double phi_deg) { return spherical_direction(theta_deg * kDegree, phi_deg * kDegree); }

// The single model of eval, albedo and sample, checked for options it does not use; its options in `used` if given.
std::unique_ptr<bsdf::Bsdf> single_model(const BrdfArgs& a, bsdf::ModelOptions* used = nullptr) {
    const bsdf::ModelOptions o = model_options(a, a.model);
    check_given_options_apply(a, {o}, {bsdf::to_string(o.model)});
    if (used) *used = o;
    return build_model(o);
}

// --psd measured: one warning with the count of directions whose first-order frequency lies beyond the band the map
// or profile resolves (bsdf/measured_band.hpp; Python's Bsdf.eval warns alike).
void warn_beyond_the_band(const bsdf::ModelOptions& o, const std::vector<std::pair<Vec3, Vec3>>& directions,
                          double lambda_nm) {
    const auto band = bsdf::measured_band(o.surface);
    if (!band) return;
    const auto beyond = std::count_if(directions.begin(), directions.end(),
                                      [&](const auto& d) { return band->beyond(d.first, d.second, lambda_nm); });
    print_note("brdf", bsdf::beyond_band_warning(*band, static_cast<std::size_t>(beyond), directions.size(), lambda_nm));
}

void eval(const BrdfArgs& a) {
    check_common(a);
    if (a.theta_i.size() != 1) fail("--theta-i takes one angle for brdf eval, got {}", a.theta_i.size());
    if (a.theta_o.empty()) fail("--theta-o is required");
    for (double t : a.theta_o) require_theta(t, "--theta-o");
    bsdf::ModelOptions options;
    const auto model = single_model(a, &options);
    const std::vector<double> phis = a.phi_o.empty() ? std::vector<double>{a.phi_i + 180.0} : a.phi_o;
    const Vec3 wi = incident(a.theta_i[0], a.phi_i);
    for (double p : phis) require_finite(p, "--phi-o");
    // Evaluated first, so that an error (a wavelength outside the material's data) prints nothing but itself.
    std::string rows = "theta_o,phi_o,brdf\n";
    std::vector<std::pair<Vec3, Vec3>> directions;
    for (double t : a.theta_o)
        for (double p : phis) {
            directions.emplace_back(wi, incident(t, p));
            rows += fmt::format("{},{},{}\n", format_number(t), format_number(p),
                                format_number(model->eval(wi, directions.back().second, a.wavelength)));
        }
    std::fputs(rows.c_str(), stdout);
    warn_beyond_the_band(options, directions, a.wavelength);
}

void albedo(const BrdfArgs& a) {
    check_common(a);
    if (a.theta_i.size() != 1) fail("--theta-i takes one angle for brdf albedo, got {}", a.theta_i.size());
    const auto model = single_model(a);
    const auto r = bsdf::directional_albedo(*model, a.theta_i[0] * kDegree, a.wavelength, a.phi_i * kDegree);
    std::printf("albedo = %s\nspecular = %s\nerror = %s\n", format_number(r.total()).c_str(),
                format_number(r.specular).c_str(), format_number(r.error).c_str());
}

void sample(const BrdfArgs& a) {
    check_common(a);
    if (a.theta_i.size() != 1) fail("--theta-i takes one angle for brdf sample, got {}", a.theta_i.size());
    if (a.count <= 0) fail("--count must be > 0, got {}", a.count);
    if (a.seed < 0) fail("--seed must be >= 0, got {}", a.seed);
    const auto model = single_model(a);
    const Vec3 wi = incident(a.theta_i[0], a.phi_i);
    std::mt19937_64 rng(static_cast<std::uint64_t>(a.seed));
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    model->eval(wi, wi, a.wavelength);  // a wavelength outside the material's data fails before any output
    std::printf("x,y,z,weight,pdf,delta\n");
    for (long long n = 0; n < a.count; ++n) {
        const double ul = uniform(rng), u1 = uniform(rng), u2 = uniform(rng);
        const auto s = model->sample(wi, a.wavelength, ul, Vec2(u1, u2));
        if (!s) {  // no direction drawn (below the horizon): a row of zeros, so that the mean weight is the albedo
            std::printf("0,0,0,0,0,0\n");
            continue;
        }
        std::printf("%s,%s,%s,%s,%s,%d\n", format_number(s->wo.x).c_str(), format_number(s->wo.y).c_str(),
                    format_number(s->wo.z).c_str(), format_number(s->weight).c_str(),
                    format_number(s->pdf).c_str(), s->delta ? 1 : 0);
    }
}

// The files the models read, which no output may replace.
void declare_inputs(OutputFiles& files, const BrdfArgs& a) {
    files.input(a.surface_file, "--surface");
    files.input(a.material, "--material");
}

void slice(const BrdfArgs& a) {
    if (a.plot.empty() && a.csv.empty()) fail("brdf slice needs --plot out.png and/or --csv out.csv");
    const std::string csv = a.csv.empty() ? std::filesystem::path(a.plot).replace_extension(".csv").string() : a.csv;
    OutputFiles files;
    declare_inputs(files, a);
    files.output(csv, a.csv.empty() ? "--plot's CSV" : "--csv");
    if (!a.plot.empty()) files.output(a.plot, "--plot");
    check_common(a);
    if (!a.models.empty() && std::count(a.given.begin(), a.given.end(), "model"))
        fail("brdf slice takes either --model or --models, not both");
    const std::vector<std::string> names = a.models.empty() ? std::vector<std::string>{a.model} : a.models;
    std::vector<bsdf::ModelOptions> options;
    for (const auto& n : names) options.push_back(model_options(a, n));
    check_given_options_apply(a, options, names);
    std::vector<std::unique_ptr<bsdf::Bsdf>> models;
    for (const auto& o : options) models.push_back(build_model(o));
    std::ostringstream table;
    for (std::size_t m = 0; m < models.size(); ++m)
        bsdf::write_slice_csv(table, names[m], *models[m], a.theta_i, a.phi_i, a.wavelength, m == 0);
    files.write(csv, table.str());
    // The slices' directions, counted against the first measured model's band (one surface for all).
    for (const bsdf::ModelOptions& o : options)
        if (bsdf::measured_band(o.surface)) {
            std::vector<std::pair<Vec3, Vec3>> directions;
            for (double ti : a.theta_i)
                for (double t : bsdf::slice_angles())
                    directions.emplace_back(incident(ti, a.phi_i), bsdf::slice_direction(t, a.phi_i));
            warn_beyond_the_band(o, directions, a.wavelength);
            break;
        }
    if (!a.plot.empty())
        files.write_with(a.plot, [&](const std::filesystem::path& png) {
            run_plot_script("brdf_slice.py",
                            {files.staged(csv).string(), png.string(), fmt::format("{} nm", format_number(a.wavelength))});
        });
    files.commit();
    std::printf("wrote %s%s%s\n", printable_path(csv).c_str(), a.plot.empty() ? "" : " and ",
                printable_path(a.plot).c_str());
}

// The surface and material options shared by every brdf subcommand.
// brdf export: the model tabulated in the RGL measured format (bsdf/rgl_export.hpp) and, if it has a coherent
// specular part, that part's reflectance beside it (FILE.specular.csv), which the file cannot hold.
void export_rgl_file(const BrdfArgs& a) {
    if (a.format != "rgl-spectral" && a.format != "rgl-rgb")
        fail("--format must be one of rgl-spectral | rgl-rgb, got '{}'", printable(a.format));
    if (a.output.empty()) fail("-o FILE.bsdf is required");
    bsdf::check_rgl_accuracy({}, a.tolerance_percent, "--tolerance", a.output);  // the value, before the work
    const std::filesystem::path out(a.output);
    const std::string side = a.output + ".specular.csv";
    OutputFiles files;
    declare_inputs(files, a);
    files.output(out, "-o");
    files.output(side, "-o's specular CSV");
    const auto model = single_model(a);
    bsdf::RglExportOptions o = a.export_options;
    o.rgb = a.format == "rgl-rgb";
    o.tolerance_percent = a.tolerance_percent;
    if (model->isotropic() && given(a, "phi_i_count")) fail("--phi-i-count applies to anisotropic surfaces only");
    if (o.rgb && (given(a, "lambda_step"))) fail("--lambda-step applies to --format rgl-spectral only");
    bsdf::check_rgl_export_options(o, model->isotropic());  // counts, step and memory before any work
    // The delta part: its reflectance over incidence and wavelength.
    std::vector<double> thetas, lambdas;
    for (int t = 0; t <= 89; ++t) thetas.push_back(t);
    for (double l = 360; l <= 830 + 1e-9; l += 10) lambdas.push_back(l);
    const bsdf::DeltaTable delta = bsdf::delta_table(*model, thetas, lambdas);
    const double delta_peak = *std::max_element(delta.reflectance.begin(), delta.reflectance.end());
    std::optional<bsdf::SpecularAsLobe> with_lobe;
    if (given(a, "specular_lobe")) with_lobe.emplace(*model, a.specular_lobe_deg * kDegree);
    const bsdf::Bsdf& tabulated = with_lobe ? static_cast<const bsdf::Bsdf&>(*with_lobe) : *model;
    if (with_lobe) o.mirror_exclusion_rad = with_lobe->core_rad();
    // The size before the work: an anisotropic spectral file over the full circle of azimuths reaches gigabytes.
    const std::size_t most = o.tolerance_percent > 0 ? std::max(bsdf::kMaxRglRefinedIncidences, std::size_t(o.theta_i_count))
                                                     : std::size_t(o.theta_i_count);
    std::printf("writing %s: %.0f MB at %d incidences%s (docs/PERFORMANCE.md \"RGL export\")\n",
                printable_path(a.output).c_str(), bsdf::rgl_export_bytes(o, model->isotropic(), std::size_t(o.theta_i_count)) / 1e6,
                o.theta_i_count,
                most > std::size_t(o.theta_i_count)
                    ? fmt::format(", up to {:.0f} MB if the refinement adds incidences up to {}",
                                  bsdf::rgl_export_bytes(o, model->isotropic(), most) / 1e6, most).c_str()
                    : "");
    std::fflush(stdout);
    const std::string description =
        fmt::format("surfscatter {} export ({}{})", model->name(), a.format,
                    with_lobe ? fmt::format(", specular part as a {} deg lobe", format_number(a.specular_lobe_deg)) : "");
    const bsdf::RglData data = bsdf::export_rgl(tabulated, o, description);
    files.write_with(out, [&](const std::filesystem::path& tmp) { bsdf::write_rgl(tmp, data); });
    const bool side_csv = !with_lobe && delta_peak > 0;
    if (side_csv) {
        std::string csv = "theta_deg";
        for (double l : lambdas) csv += fmt::format(",R_{}nm", format_number(l));
        csv += "\n";
        for (std::size_t i = 0; i < thetas.size(); ++i) {
            csv += format_number(thetas[i]);
            for (std::size_t k = 0; k < lambdas.size(); ++k) {
                csv += ',';  // not `"," + std::string`: g++ 12's false -Wrestrict
                csv += format_number(delta.reflectance[i * lambdas.size() + k]);
            }
            csv += "\n";
        }
        files.write(side, csv);
    }
    // The written file read back from disk and evaluated as Mitsuba 3 and pbrt-v4 do, against the model.
    const bsdf::RglAccuracy acc = bsdf::rgl_file_accuracy(tabulated, files.staged(out), o);
    files.commit();
    std::printf("wrote %s (%zu incidences x %zu azimuths, %zu x %zu samples, %s)\n", printable_path(a.output).c_str(),
                data.theta_i.size(), data.phi_i.size(), data.rows, data.cols,
                o.rgb ? "rgb" : fmt::format("{} wavelengths {}-{} nm", data.wavelengths.size(), data.wavelengths.front(),
                                            data.wavelengths.back()).c_str());
    if (with_lobe)
        std::printf("the coherent specular part (reflectance up to %s) is in the file as a lobe of %s deg about the "
                    "mirror direction (docs/RENDERER.md \"Exporting to Mitsuba 3 and pbrt-v4\")\n",
                    format_number(delta_peak).c_str(), format_number(a.specular_lobe_deg).c_str());
    if (side_csv)
        std::printf("wrote %s: the coherent specular (delta) reflectance, up to %s, which the file leaves out "
                    "(--specular-lobe DEG puts it in the file; docs/RENDERER.md \"Exporting to Mitsuba 3 and pbrt-v4\")\n",
                    printable_path(side).c_str(), format_number(delta_peak).c_str());
    std::printf("accuracy: the file against the model at %zu directions (random and from the model's sampler, "
                "where f >= 1 %% of its peak and theta_o <= 80 deg%s): worst %.2f %% at %s, rms %.2f %%\n",
                acc.compared,
                with_lobe ? fmt::format(", outside the lobe's core ({} deg about the mirror direction, whose energy "
                                        "RglExport.SpecularLobeCarriesTheDeltasEnergy measures)",
                                        format_number(o.mirror_exclusion_rad / kDegree)).c_str()
                          : "",
                100 * acc.worst, bsdf::rgl_accuracy_where(acc).c_str(), 100 * acc.rms);
    if (acc.jump_band > 0)
        std::printf("the model jumps on a circle about the specular direction (the micro lobe's edge); %zu directions "
                    "within %.0f %% of its radius, compared apart: worst %.2f %% (no table follows a jump; "
                    "docs/MODELS.md \"Export to the RGL format\")\n",
                    acc.jump_compared, 100 * acc.jump_band, 100 * acc.jump_worst);
    bsdf::check_rgl_accuracy(acc, a.tolerance_percent, "--tolerance", a.output);
}

void add_model_options(CLI::App* cmd, BrdfArgs& a) {
    cmd->add_option("--model", a.model, bsdf::choices("model") + " (default ghs; docs/MODELS.md)");
    cmd->add_option("--method", a.method, "GHS lobe: exact (tabulated S_g, default) | refit (paper's KC series)");
    cmd->add_option("--truncation", a.truncation, "refit orders: three_sigma (default) | poisson_mass");
    cmd->add_option("--epsilon", a.epsilon, "poisson_mass: Poisson mass left out (default 1e-6)");
    cmd->add_option("--fresnel", a.fresnel, "incident (R(theta_i), default) | half (F(theta_d)) | rr (Rayleigh-Rice)");
    cmd->add_flag("--no-renormalization", a.no_renormalization, "sigma_h instead of sigma_rel and K = 1");
    cmd->add_option("--ssa-form", a.ssa_form, "ghs_ssa: energy (default) | strict");
    cmd->add_option("--alpha", a.alpha, "ggx_stats roughness given (implies --alpha-from none)");
    cmd->add_option("--alpha-from", a.alpha_from, "ggx_stats roughness: " + bsdf::choices("alpha_from") +
                                                      " (default measured: the surface's rms slope; none with --alpha)");
    cmd->add_option("--smoothing", a.smoothing, "Gaussian smoothing std (um) for --alpha-from smoothed");
    cmd->add_option("--cutoff-wavelengths", a.cutoff_wavelengths, "two_scale: split at zeta_c = k/N (default 100)");
    cmd->add_option("--macro-ndf", a.macro_ndf, "two_scale macro NDF: ggx (default) | beckmann");
    cmd->add_option("--material", a.material, "required: built-in metal (Au, Ag, Al, Cu, ...), n,k file, or perfect "
                                              "(a perfect conductor, R = 1)");
    cmd->add_option("--psd", a.psd, "surface statistics: kc | gaussian | file (KC fitted to --surface) | measured "
                                    "(the --surface map's own spectrum: --measured-spectrum)");
    cmd->add_option("--psd-fit", a.psd_fit, "--psd file: the KC fitted to --surface is isotropic (default) | elliptical "
                                            "(LU, LV and lay angle fitted to the 2-D PSD; docs/SURFACE.md)");
    cmd->add_option("--sigma", a.sigma, "rms height (um); --sigma, --corr-length, --gamma alone mean --psd kc");
    cmd->add_option("--corr-length", a.corr_length, "correlation length (um): KC L, or Gaussian l");
    cmd->add_option("--gamma", a.gamma, "KC exponent gamma > 1");
    cmd->add_option("--corr-length-v", a.corr_length_v, "elliptical surface: correlation length LV (um) across the "
                                                        "lay, --corr-length being LU along it (default LV = LU)");
    cmd->add_option("--lay-angle", a.lay_angle, "lay direction u (deg from phi = 0 towards phi = 90, default 0); "
                                                "docs/SURFACE.md \"Anisotropy\"");
    cmd->add_option("--surface", a.surface_file, "height map (any format `surface info` reads): KC fitted to it "
                                                 "(--psd file, a map's default) or its own PSD (--psd measured, a "
                                                 "profile's default: docs/HEIGHTMAPS.md \"Profiles\")");
    add_preparation_options(cmd, a.preparation, "--surface");
    cmd->add_option("--measured-spectrum", a.measured_spectrum,
                    "--psd measured: 2d (default: ghs and ghs_ssa on the map's 2-D spectrum) | ring (its ring "
                    "average, as before); docs/SURFACE.md \"The 2-D measured lobes\"");
}

// Those and the wavelength and incidence of eval, albedo, sample and slice.
void add_model_options(CLI::App* cmd, BrdfArgs& a, bool several_thetas) {
    add_model_options(cmd, a);
    cmd->add_option("--wavelength", a.wavelength, "wavelength (nm)")->required();
    if (several_thetas)
        add_number_list(cmd, "--theta-i", a.theta_i, "incidence angles (deg), comma separated")->required();
    else
        cmd->add_option("--theta-i", a.theta_i, "incidence angle (deg)")->required();
    cmd->add_option("--phi-i", a.phi_i, "incidence azimuth (deg, default 0; relative to the lay for an elliptical surface)");
}

const Command command("brdf", [](CLI::App& app) {
    CLI::App* brdf_cmd = app.add_subcommand("brdf", "Scattering models: evaluate, albedo, sample, plot slices");
    brdf_cmd->require_subcommand(1);
    auto a = std::make_shared<BrdfArgs>();

    CLI::App* eval_cmd = brdf_cmd->add_subcommand("eval", "CSV theta_o,phi_o,brdf for every (theta_o, phi_o)");
    add_model_options(eval_cmd, *a, false);
    add_number_list(eval_cmd, "--theta-o", a->theta_o, "outgoing angles (deg), comma separated")->required();
    add_number_list(eval_cmd, "--phi-o", a->phi_o, "outgoing azimuths (deg, default phi_i + 180: specular side)");
    eval_cmd->callback([a, eval_cmd] {
        a->given = given_options(eval_cmd);
        eval(*a);
    });

    CLI::App* albedo_cmd = brdf_cmd->add_subcommand("albedo", "directional albedo and its specular (delta) part");
    add_model_options(albedo_cmd, *a, false);
    albedo_cmd->callback([a, albedo_cmd] {
        a->given = given_options(albedo_cmd);
        albedo(*a);
    });

    CLI::App* sample_cmd = brdf_cmd->add_subcommand("sample", "CSV x,y,z,weight,pdf,delta of every draw (0,0,0,0,0,0 where none was drawn); mean weight = albedo");
    add_model_options(sample_cmd, *a, false);
    sample_cmd->add_option("--count", a->count, "number of samples (default 1000)");
    sample_cmd->add_option("--seed", a->seed, "random seed (default 1)");
    sample_cmd->callback([a, sample_cmd] {
        a->given = given_options(sample_cmd);
        sample(*a);
    });

    CLI::App* export_cmd = brdf_cmd->add_subcommand(
        "export", "the model as an RGL measured BSDF file for Mitsuba 3 / pbrt-v4 `measured` (docs/RENDERER.md)");
    add_model_options(export_cmd, *a);
    export_cmd->add_option("--format", a->format, "rgl-spectral (360-1000 nm; Mitsuba 3 and pbrt-v4) | rgl-rgb "
                                                  "(linear sRGB; Mitsuba 3)")->required();
    export_cmd->add_option("-o,--output", a->output, "output FILE.bsdf")->required();
    export_cmd->add_option("--theta-i-count", a->export_options.theta_i_count, "incidences over 0-88 deg (default 16)");
    export_cmd->add_option("--phi-i-count", a->export_options.phi_i_count,
                           "anisotropic surfaces: incidence azimuths over 360 deg (default 17)");
    export_cmd->add_option("--sample-resolution", a->export_options.sample_resolution,
                           "nodes per side of the spectral table (default 64)");
    export_cmd->add_option("--ndf-resolution", a->export_options.ndf_resolution,
                           "nodes per side of the NDF and VNDF tables (default 128)");
    export_cmd->add_option("--lambda-step", a->export_options.lambda_step_nm,
                           "rgl-spectral: wavelength step over 360-1000 nm (default 3.2 nm)");
    export_cmd->add_option("--threads", a->export_options.threads, "worker threads (default 0: all)");
    export_cmd->add_option("--specular-lobe", a->specular_lobe_deg,
                           "carry the coherent specular (delta) part in the file as a lobe of this width (deg, "
                           "< 11.5) about the mirror direction, instead of beside it as FILE.specular.csv");
    export_cmd->add_option("--tolerance", a->tolerance_percent,
                           "largest relative error (%) of the written file against the model accepted, measured after "
                           "writing; beyond it exit 2 (default 2)");
    export_cmd->callback([a, export_cmd] {
        a->given = given_options(export_cmd);
        require_thread_count(a->export_options.threads, "--threads");
        export_rgl_file(*a);
    });

    CLI::App* slice_cmd = brdf_cmd->add_subcommand("slice", "in-plane log-scale slices of several models (CSV + PNG)");
    add_model_options(slice_cmd, *a, true);
    add_string_list(slice_cmd, "--models", a->models, "models to overlay, comma separated; model:psd picks the surface "
                                                      "statistics per model (ghs:file,ghs:measured)");
    slice_cmd->add_option("--plot", a->plot, "output PNG");
    slice_cmd->add_option("--csv", a->csv, "output CSV (default: the PNG path with .csv)");
    slice_cmd->callback([a, slice_cmd] {
        a->given = given_options(slice_cmd);
        slice(*a);
    });
});

}  // namespace

}  // namespace surfscatter::cli
