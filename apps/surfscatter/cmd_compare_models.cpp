// surfscatter compare-models: one view of scenes/photo-setup rendered with every scattering model, as one sheet.
#include <filesystem>

#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::cli {

namespace {

struct CompareArgs {
    std::string scene = "scenes/photo-setup/scene.xml";  // relative to the working directory (the repository root)
    int view = 1;
    std::vector<std::string> defines;
    int spp = 16;
    int width = 384;
    int height = 288;
    int threads = 0;
    double smoothing = 1.0;
    std::string output_dir = "out/compare-models";
    bool quiet = false;
};

struct Panel {
    std::string name;   // file stem
    std::string label;  // sheet caption
    std::map<std::string, std::string> defines;
};

// The models of the supplemental: Figures 3/5/7 (GGX smoothed and measured, SSA GHS, full GHS) and 4/6/8
// (two-scale at 50, 100 and 150 wavelengths).
std::vector<Panel> panels(double smoothing) {
    return {
        {"ggx_smoothed", fmt::format("GGX (smoothed {} um)", smoothing),
         {{"model", "ggx_stats"}, {"alpha_from", "smoothed"}, {"smoothing", fmt::format("{}", smoothing)}}},
        {"ggx_measured", "GGX (measured)", {{"model", "ggx_stats"}, {"alpha_from", "measured"}}},
        {"ghs_ssa", "SSA GHS", {{"model", "ghs_ssa"}}},
        {"ghs", "GHS", {{"model", "ghs"}}},
        {"two_scale_50", "two-scale 50 lambda", {{"model", "two_scale"}, {"cutoff", "50"}}},
        {"two_scale_100", "two-scale 100 lambda", {{"model", "two_scale"}, {"cutoff", "100"}}},
        {"two_scale_150", "two-scale 150 lambda", {{"model", "two_scale"}, {"cutoff", "150"}}},
    };
}

void run(const CompareArgs& args) {
    if (args.view < 1 || args.view > 3) fail("--view must be 1, 2 or 3, got {}", args.view);
    require_positive(args.spp, "--spp");
    require_positive(args.width, "--width");
    require_positive(args.height, "--height");
    require_non_negative(args.smoothing, "--smoothing");
    std::map<std::string, std::string> common;
    for (const std::string& item : args.defines) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0) fail("-D expects name=value, got '{}'", item);
        common[item.substr(0, eq)] = item.substr(eq + 1);
    }
    common["view"] = std::to_string(args.view);
    common["width"] = std::to_string(args.width);
    common["height"] = std::to_string(args.height);
    const std::filesystem::path dir(args.output_dir);
    std::filesystem::create_directories(dir);
    install_interrupt_handler();

    std::vector<std::string> sheet_args;
    const auto list = panels(args.smoothing);
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Panel& panel = list[i];
        std::map<std::string, std::string> defines = common;
        for (const auto& [k, v] : panel.defines) defines[k] = v;
        auto scene = render::load_scene(args.scene, defines);
        render::RenderOptions options;
        options.spp = args.spp;
        options.threads = args.threads;
        options.progress = !args.quiet;
        if (!args.quiet) std::fprintf(stderr, "[%zu/%zu] %s\n", i + 1, list.size(), panel.label.c_str());
        render::RenderStats stats;
        const render::Film film = render::render(*scene, options, &stats);
        const std::filesystem::path exr = dir / (panel.name + ".exr");
        render::write_film(film, scene->film, exr);
        sheet_args.push_back(panel.label + "=" + (dir / (panel.name + ".png")).string());
        if (stats.interrupted) break;
    }
    // Two rows as in the supplemental: the four models of Figs. 3/5/7, then the two-scale cutoffs of Figs. 4/6/8.
    if (sheet_args.size() > 4) sheet_args.insert(sheet_args.begin() + 4, "-=");
    sheet_args.insert(sheet_args.begin(), {(dir / "sheet.png").string(),
                                           fmt::format("photo-setup view {}, {} spp", args.view, args.spp), "4"});
    run_plot_script("sheet_compare.py", sheet_args);
    std::fprintf(stderr, "comparison sheet: %s\n", (dir / "sheet.png").c_str());
}

const Command command("compare-models", [](CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand(
        "compare-models", "Render one photo-setup view with GGX (smoothed, measured), SSA GHS, GHS and two-scale "
                          "(50/100/150 lambda) and lay them out as one labelled sheet (PNG)");
    sub->add_option("--scene", args->scene, "Scene with $model, $alpha_from, $smoothing, $cutoff, $view parameters");
    sub->add_option("--view", args->view, "Camera view 1 (near-normal), 2 or 3 (grazing)");
    sub->add_option("-D", args->defines, "Extra scene parameter name=value (e.g. sigma=0.2)")->allow_extra_args(false);
    sub->add_option("--spp", args->spp, "Samples per pixel");
    sub->add_option("--width", args->width, "Image width");
    sub->add_option("--height", args->height, "Image height");
    sub->add_option("--threads", args->threads, "Worker threads (default: all cores)");
    sub->add_option("--smoothing", args->smoothing, "Gaussian smoothing std for the smoothed GGX, um");
    sub->add_option("-o,--output-dir", args->output_dir, "Directory for the renders (EXR + PNG) and sheet.png");
    sub->add_flag("--quiet", args->quiet, "No progress bars");
    sub->callback([args] { run(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
