// surfscatter metals: normal-incidence reflectance spectra of metals and their colour under a black-body lamp,
// written as CSV/JSON data and PNG plots (the `make demo` summary of the spectral core).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::cli {

namespace {

struct MetalsArgs {
    std::filesystem::path out = "out";
    std::vector<std::string> materials;
    double temperature = 2700;
    double min_wavelength = 380, max_wavelength = 780;
    bool plot = true;
};

int to_8bit(double encoded) { return static_cast<int>(std::lround(std::clamp(encoded, 0.0, 1.0) * 255.0)); }

void run_metals(MetalsArgs a) {
    spectrum::require_blackbody_temperature(a.temperature, "--temperature");
    require_positive(a.min_wavelength, "--min-wavelength");
    require_finite(a.max_wavelength, "--max-wavelength");
    if (!(a.max_wavelength > a.min_wavelength))
        fail("--max-wavelength {} must exceed --min-wavelength {}", a.max_wavelength, a.min_wavelength);
    std::error_code ec;
    if (std::filesystem::exists(a.out, ec) && !std::filesystem::is_directory(a.out, ec))
        fail("--out {} exists and is not a directory", a.out.string());
    std::filesystem::create_directories(a.out);
    const auto reflectance_path = a.out / "metals_reflectance.csv", swatch_path = a.out / "metals_swatches.csv",
               json_path = a.out / "metals_swatches.json", reflectance_png = a.out / "metals_reflectance.png",
               swatch_png = a.out / "metals_swatches.png";
    OutputFiles files;
    for (const auto& m : a.materials) files.input(m, "--material");
    files.output(reflectance_path, "--out's reflectance CSV");
    files.output(swatch_path, "--out's swatch CSV");
    files.output(json_path, "--out's swatch JSON");
    if (a.plot) {
        files.output(reflectance_png, "--out's reflectance plot");
        files.output(swatch_png, "--out's swatch plot");
    }
    if (a.materials.empty()) a.materials = material::builtin_metal_names();
    std::vector<material::Conductor> metals;
    for (const auto& m : a.materials) metals.push_back(material::Conductor::from_name(m));

    // Normal-incidence reflectance, 1 nm steps.
    {
        std::ostringstream csv;
        csv << "wavelength_nm";
        for (const auto& m : metals) csv << "," << m.name();
        csv << "\n";
        for (double l = a.min_wavelength; l <= a.max_wavelength + 1e-9; l += 1.0) {
            csv << format_number(l);
            for (const auto& m : metals) csv << "," << format_number(m.reflectance(1.0, l));
            csv << "\n";
        }
        files.write(reflectance_path, csv.str());
    }

    // Colour under the lamp: XYZ with the perfect reflector at Y = 1, then either white-balanced to the lamp
    // (Bradford to D65: the colour an adapted eye or a camera set to the lamp sees) or as lit, scaled so that the
    // perfect reflector's largest sRGB channel is 1.
    const auto lamp = [&](double l) { return spectrum::blackbody_radiance(l, a.temperature); };
    const Vec3 white = spectrum::blackbody_white_xyz(a.temperature);
    const spectrum::Mat3 balance = spectrum::white_balance_to_d65(white);
    const Vec3 white_rgb = spectrum::xyz_to_linear_srgb(white);
    const double as_lit_scale = 1.0 / std::max({white_rgb.x, white_rgb.y, white_rgb.z});
    nlohmann::json json;
    json["illuminant"] = fmt::format("blackbody {} K", a.temperature);
    json["geometry"] = "normal incidence, specular";
    json["white_balance"] = "Bradford from the lamp white to D65, then linear sRGB (IEC 61966-2-1)";
    json["as_lit_scale"] = as_lit_scale;
    std::ostringstream csv;
    csv << "metal,X,Y,Z,x,y,r_linear,g_linear,b_linear,r8,g8,b8,r_linear_as_lit,g_linear_as_lit,b_linear_as_lit,"
           "r8_as_lit,g8_as_lit,b8_as_lit\n";
    for (const auto& m : metals) {
        const Vec3 xyz = spectrum::reflectance_to_xyz([&](double l) { return m.reflectance(1.0, l); }, lamp);
        const Vec2 xy = spectrum::chromaticity(xyz);
        const Vec3 balanced = spectrum::xyz_to_linear_srgb(balance * xyz);
        const Vec3 as_lit = spectrum::xyz_to_linear_srgb(xyz) * as_lit_scale;
        const Vec3 balanced8 = spectrum::srgb_encode(balanced), as_lit8 = spectrum::srgb_encode(as_lit);
        csv << fmt::format("{},{},{},{},{},{}", m.name(), format_number(xyz.x), format_number(xyz.y),
                           format_number(xyz.z), format_number(xy.x), format_number(xy.y));
        const auto write_linear = [&](const Vec3& v) {
            for (int c = 0; c < 3; ++c) csv << "," << format_number(v[c]);
        };
        const auto write_8bit = [&](const Vec3& v) {
            for (int c = 0; c < 3; ++c) csv << "," << to_8bit(v[c]);
        };
        write_linear(balanced);
        write_8bit(balanced8);
        write_linear(as_lit);
        write_8bit(as_lit8);
        csv << "\n";
        json["metals"].push_back({{"metal", m.name()},
                                  {"XYZ", {xyz.x, xyz.y, xyz.z}},
                                  {"xy", {xy.x, xy.y}},
                                  {"linear_srgb", {balanced.x, balanced.y, balanced.z}},
                                  {"srgb8", {to_8bit(balanced8.x), to_8bit(balanced8.y), to_8bit(balanced8.z)}},
                                  {"linear_srgb_as_lit", {as_lit.x, as_lit.y, as_lit.z}},
                                  {"srgb8_as_lit", {to_8bit(as_lit8.x), to_8bit(as_lit8.y), to_8bit(as_lit8.z)}}});
    }
    files.write(swatch_path, csv.str());
    files.write(json_path, json.dump(2) + "\n");
    if (a.plot)
        files.write_together({reflectance_png, swatch_png}, [&](const std::vector<std::filesystem::path>& png) {
            run_plot_script("metals.py", {files.staged(reflectance_path).string(), files.staged(json_path).string(),
                                          png[0].string(), png[1].string()});
        });
    files.commit();  // on a full disk nothing is left behind
    for (const auto& path : {reflectance_path, swatch_path, json_path}) std::printf("%s\n", printable_path(path).c_str());
    if (a.plot) std::printf("%s\n%s\n", printable_path(reflectance_png).c_str(), printable_path(swatch_png).c_str());
}

const Command command("metals", [](CLI::App& app) {
    auto args = std::make_shared<MetalsArgs>();
    auto* sub = app.add_subcommand(
        "metals", "Write normal-incidence reflectance spectra and lamp-lit colour swatches of metals (CSV, JSON, PNG)");
    sub->add_option("--out", args->out, "Output directory")->capture_default_str();
    add_string_list(sub, "--material", args->materials,
                    "Metals (built-in names or .yml/.csv files); default: all built-ins");
    sub->add_option("--temperature", args->temperature, "Black-body lamp temperature in K")->capture_default_str();
    sub->add_option("--min-wavelength", args->min_wavelength, "Start of the reflectance plot, nm")->capture_default_str();
    sub->add_option("--max-wavelength", args->max_wavelength, "End of the reflectance plot, nm")->capture_default_str();
    sub->add_flag("!--no-plot", args->plot, "Write only the CSV/JSON data, no PNG");
    sub->callback([args] { run_metals(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
