// surfscatter surface synth | fit: random KC height maps (.gsf) and KC fits of measured height maps.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/surface/height_map_io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::cli {

namespace {

struct SynthArgs {
    std::string model = "kc";
    double sigma = 0, corr_length = 0, spacing = 0;
    std::optional<double> gamma;
    long long size = 0;
    unsigned long long seed = 1;
    std::string output;
    std::string title;
};

struct FitArgs {
    std::string input;
    std::optional<double> spacing, height_unit, smoothing;
    std::size_t min_ring = surface::KcFitOptions{}.min_ring;
    double max_zeta_fraction = surface::KcFitOptions{}.max_nyquist_fraction;
    std::string plot, csv;
};

std::unique_ptr<surface::RadialStatistics> synthesis_model(const SynthArgs& args) {
    require_positive(args.sigma, "--sigma");
    require_positive(args.corr_length, "--corr-length");
    if (args.model == "kc") {
        if (!args.gamma) fail("--gamma is required for --model kc");
        require_finite(*args.gamma, "--gamma");
        if (!(*args.gamma > 1.0))
            fail("--gamma must be > 1 (the KC variance is infinite otherwise), got {}", *args.gamma);
        return std::make_unique<surface::KCorrelation>(args.sigma, args.corr_length, *args.gamma);
    }
    if (args.model == "gaussian") {
        if (args.gamma) fail("--gamma applies to --model kc only");
        return std::make_unique<surface::GaussianAcv>(args.sigma, args.corr_length);
    }
    fail("--model must be kc or gaussian, got '{}'", args.model);
}

void synth(const SynthArgs& args) {
    const auto model = synthesis_model(args);
    surface::require_valid_spacing(args.spacing, "--spacing");
    if (args.size < static_cast<long long>(surface::kMinHeightMapSize))
        fail("--size must be at least {} samples, got {}", surface::kMinHeightMapSize, args.size);
    if (std::filesystem::path(args.output).extension() != ".gsf")
        fail("-o must name a .gsf file, got '{}'", args.output);
    const auto n = static_cast<std::size_t>(args.size);
    surface::HeightMap map = surface::synthesize_surface(*model, {n, n, args.spacing}, args.seed);
    map.title = args.title.empty()
                    ? fmt::format("{} sigma_h={} um L_c={} um{} seed={}", args.model, args.sigma, args.corr_length,
                                  args.gamma ? fmt::format(" gamma={}", *args.gamma) : "", args.seed)
                    : args.title;
    surface::write_gsf(map, args.output);
}

void write_psd_csv(const surface::SurfaceFit& fit, const std::string& path) {
    const surface::KCorrelation model(fit.kc.sigma_h_um, fit.kc.corr_length_um, fit.kc.gamma);
    std::ofstream out(path);
    if (!out) fail("--csv: cannot open '{}' for writing", path);
    out << "zeta,psd,count,kc_fit,in_band\n";
    const auto& r = fit.radial;
    for (std::size_t i = 0; i < r.zeta.size(); ++i) {
        const bool in_band = r.zeta[i] >= fit.kc.zeta_min && r.zeta[i] <= fit.kc.zeta_max;
        out << format_number(r.zeta[i]) << ',' << format_number(r.psd[i]) << ',' << format_number(r.count[i]) << ','
            << format_number(model.psd(r.zeta[i])) << ',' << (in_band ? 1 : 0) << '\n';
    }
    if (!out) fail("--csv: write error on '{}'", path);
}

void fit(const FitArgs& args) {
    if (args.spacing) surface::require_valid_spacing(*args.spacing, "--spacing");
    if (args.height_unit) require_positive(*args.height_unit, "--height-unit");
    if (args.smoothing) require_positive(*args.smoothing, "--smoothing");
    const surface::HeightMap map = surface::read_height_map(args.input, args.spacing, args.height_unit);
    surface::KcFitOptions options;
    options.min_ring = args.min_ring;
    options.max_nyquist_fraction = args.max_zeta_fraction;
    const surface::SurfaceFit result = surface::fit_surface(map, options);

    std::printf("sigma_h = %s\n", format_number(result.kc.sigma_h_um).c_str());
    std::printf("corr_length = %s\n", format_number(result.kc.corr_length_um).c_str());
    std::printf("gamma = %s\n", format_number(result.kc.gamma).c_str());
    std::printf("rms_slope = %s\n", format_number(result.rms_slope).c_str());
    if (args.smoothing)
        std::printf("rms_slope_smoothed = %s\n",
                    format_number(surface::rms_slope_smoothed(map, *args.smoothing)).c_str());
    std::printf("rms_slope_psd = %s\n", format_number(result.rms_slope_from_psd).c_str());
    std::printf("rms_height_map = %s\n", format_number(result.rms_height_um).c_str());
    std::printf("zeta_min = %s\n", format_number(result.kc.zeta_min).c_str());
    std::printf("zeta_max = %s\n", format_number(result.kc.zeta_max).c_str());
    std::printf("log_residual_rms = %s\n", format_number(result.kc.log_residual_rms).c_str());

    std::string csv = args.csv;
    if (csv.empty() && !args.plot.empty()) csv = std::filesystem::path(args.plot).replace_extension(".csv").string();
    if (!csv.empty()) write_psd_csv(result, csv);
    if (!args.plot.empty())
        run_plot_script("psd_fit.py",
                        {csv, args.plot,
                         fmt::format("{}: KC fit sigma_h = {:.4g} um, L_c = {:.4g} um, gamma = {:.4g}",
                                     std::filesystem::path(args.input).filename().string(), result.kc.sigma_h_um,
                                     result.kc.corr_length_um, result.kc.gamma)});
}

const Command command("surface", [](CLI::App& app) {
    CLI::App* surface_cmd = app.add_subcommand("surface", "Height maps: synthesize random surfaces, fit KC statistics");
    surface_cmd->require_subcommand(1);

    auto s = std::make_shared<SynthArgs>();
    CLI::App* synth_cmd = surface_cmd->add_subcommand("synth", "Random Gaussian surface with a KC PSD -> .gsf");
    synth_cmd->add_option("--model", s->model, "PSD model: kc (K-correlation) or gaussian (Gaussian ACV)");
    synth_cmd->add_option("--sigma", s->sigma, "rms height sigma_h (um)")->required();
    synth_cmd->add_option("--corr-length", s->corr_length, "correlation length L_c (um)")->required();
    synth_cmd->add_option("--gamma", s->gamma, "KC exponent gamma > 1 (--model kc)");
    synth_cmd->add_option("--size", s->size, "samples per side N (N x N map)")->required();
    synth_cmd->add_option("--spacing", s->spacing, "pixel spacing (um)")->required();
    synth_cmd->add_option("--seed", s->seed, "random seed (same seed, same surface)");
    synth_cmd->add_option("-o,--output", s->output, "output height map (.gsf)")->required();
    synth_cmd->add_option("--title", s->title, "Title stored in the .gsf header");
    synth_cmd->callback([s] { synth(*s); });

    auto f = std::make_shared<FitArgs>();
    CLI::App* fit_cmd = surface_cmd->add_subcommand(
        "fit", "Fit KC (sigma_h, L_c, gamma) to a height map (.gsf or CSV grid); print name = value lines");
    fit_cmd->add_option("map", f->input, "height map: .gsf, or a CSV/whitespace grid of heights in um")->required();
    fit_cmd->add_option("--spacing", f->spacing, "pixel spacing of a CSV grid (um)");
    fit_cmd->add_option("--height-unit", f->height_unit, "um per height unit of a CSV grid (default 1)");
    fit_cmd->add_option("--smoothing", f->smoothing, "also print the rms slope after Gaussian smoothing (std, um)");
    fit_cmd->add_option("--min-ring", f->min_ring, "lowest PSD ring fitted (default 4)");
    fit_cmd->add_option("--max-zeta-fraction", f->max_zeta_fraction,
                        "highest fitted frequency as a fraction of Nyquist (default 0.5)");
    fit_cmd->add_option("--plot", f->plot, "write the radial PSD and the fit as PNG (and CSV beside it)");
    fit_cmd->add_option("--csv", f->csv, "write the radial PSD and the fit as CSV");
    fit_cmd->callback([f] { fit(*f); });
});

}  // namespace

}  // namespace surfscatter::cli
