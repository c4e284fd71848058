// surfscatter fit-brdf: each model's surface statistics fitted to a measured BRDF (docs/FIT.md); OUT.json, OUT.csv,
// OUT_residuals.png, one summary line per model and the verdict on stdout.
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/inverse/fit_report.hpp"

namespace surfscatter::cli {

namespace {

struct FitArgs {
    std::string data, material, psd = "kc", output, profile;
    std::vector<std::string> models, fixes;
    std::vector<double> wavelengths;  // RGL files: the wavelengths read (default 450, 550, 650 nm)
    bool anisotropic = false;
};

std::map<std::string, double> parse_fixes(const std::vector<std::string>& fixes) {
    std::map<std::string, double> fixed;
    for (const std::string& item : fixes) {
        const auto eq = item.find('=');
        const auto value = eq == std::string::npos ? std::nullopt : to_double(std::string_view(item).substr(eq + 1));
        if (!value) fail("--fix must be NAME=VALUE (e.g. gamma=3), got '{}'", printable(item));
        if (!fixed.emplace(item.substr(0, eq), *value).second)
            fail("--fix {} is given twice", printable(item.substr(0, eq)));
    }
    return fixed;
}

void run(const FitArgs& a) {
    const bool rgl = std::filesystem::path(a.data).extension() == ".bsdf";
    if (!rgl && !a.wavelengths.empty()) fail("--wavelengths applies to RGL .bsdf data only (a CSV names its own)");
    const std::vector<double> wavelengths = a.wavelengths.empty() ? std::vector<double>{450, 550, 650} : a.wavelengths;
    const std::string out = a.output;
    const std::filesystem::path json_path = out + ".json", csv_path = out + ".csv", png_path = out + "_residuals.png";
    OutputFiles files;
    files.input(a.data, "--data");
    files.input(a.material, "--material");
    files.output(json_path, "-o's JSON");
    files.output(csv_path, "-o's CSV");
    files.output(png_path, "-o's residuals plot");
    inverse::FitOptions options;
    options.material = a.material;
    options.psd = bsdf::parse_psd(a.psd, "--psd");
    if (options.psd != bsdf::PsdKind::kc && options.psd != bsdf::PsdKind::gaussian)
        fail("--psd must be kc or gaussian for a fit, got '{}'", printable(a.psd));
    options.anisotropic = a.anisotropic;
    if (!a.profile.empty()) {
        if (rgl) fail("--profile applies to CSV data of a profile (1-D), not to an RGL .bsdf file");
        options.profile = bsdf::parse_profile_polarisation(a.profile, "--profile");
    }
    options.fixed = parse_fixes(a.fixes);
    if (!a.models.empty()) {
        options.models.clear();
        for (const std::string& m : a.models) options.models.push_back(bsdf::parse_model(m, "--model"));
    }
    const inverse::BrdfData data = rgl ? inverse::read_brdf_rgl(a.data, wavelengths) : inverse::read_brdf_csv(a.data);
    if (rgl) {
        std::string listed;
        for (double l : wavelengths) listed += (listed.empty() ? "" : ",") + format_number(l);
        std::printf("read %zu values from %s: its sample nodes at each incidence below 89 deg, at %s nm (docs/FIT.md "
                    "\"RGL measured files\")\n",
                    data.size(), printable_path(a.data).c_str(), listed.c_str());
    }
    const inverse::FitResult result = inverse::fit_brdf(data, options);
    files.write(json_path, inverse::fit_json(data, options, result).dump(2) + "\n");
    files.write(csv_path, inverse::fit_csv(data, result));
    files.write_with(png_path, [&](const std::filesystem::path& png) {
        run_plot_script("fit_brdf.py", {files.staged(csv_path).string(), files.staged(json_path).string(), png.string()});
    });
    files.commit();
    for (const auto& fit : result.fits) std::printf("%s\n", inverse::summary_line(fit).c_str());
    std::printf("%s\n", result.verdict.c_str());
    std::printf("wrote %s, %s and %s\n", printable_path(json_path).c_str(), printable_path(csv_path).c_str(),
                printable_path(png_path).c_str());
}

const Command command("fit-brdf", [](CLI::App& app) {
    auto a = std::make_shared<FitArgs>();
    auto* sub = app.add_subcommand(
        "fit-brdf", "Fit each model's surface statistics (sigma, L, gamma) to a measured BRDF: estimates, standard "
                    "errors, correlations, misfit, the best model (docs/FIT.md)");
    sub->add_option("--data", a->data,
                    "measured BRDF: CSV wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf[,brdf_stderr] "
                    "(1/sr, no cosine) or an RGL measured file .bsdf (spectral or rgb)")
        ->required();
    sub->add_option("--material", a->material,
                    "perfect, a built-in metal (Ag, Au, Al, Cu, ...) or a .yml/.csv refractive index file")
        ->required();
    add_number_list(sub, "--wavelengths", a->wavelengths,
                    "RGL .bsdf data: wavelengths read, nm, comma separated (default 450,550,650)");
    add_string_list(sub, "--model", a->models,
                    "models to fit, comma separated: " + bsdf::choices("model") + " (default all)");
    sub->add_option("--psd", a->psd, "surface statistics fitted: kc (sigma, L, gamma; default) | gaussian (sigma, L)");
    sub->add_option("--profile", a->profile,
                    "1-D data of this polarisation (s | p): rows in the plane of incidence (phi_i 0, phi_o 0 or 180), "
                    "the brdf column the scattered power per radian of a profile, as reference exact-1d gives it; "
                    "fitted with the models' 1-D forms (docs/FIT.md \"Profiles\")");
    sub->add_flag("--anisotropic", a->anisotropic, "also fit corr_length_v_um and lay_angle_deg (elliptical)");
    sub->add_option("--fix", a->fixes,
                    "hold a parameter: NAME=VALUE with NAME sigma_um, corr_length_um, gamma, corr_length_v_um or "
                    "lay_angle_deg (repeatable)");
    sub->add_option("-o", a->output, "output prefix: OUT.json, OUT.csv and OUT_residuals.png")->required();
    sub->callback([a] { run(*a); });
});

}  // namespace

}  // namespace surfscatter::cli
