// surfscatter render: a Mitsuba-style XML scene -> linear sRGB OpenEXR + sRGB PNG.
#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::cli {

namespace {

struct RenderArgs {
    std::string scene;
    std::vector<std::string> defines;
    int spp = 0;
    int threads = 0;
    long long seed = -1;
    std::string output = "render.exr";
    double exposure = 0;
    bool exposure_set = false;
    std::string white_balance;
    bool quiet = false;
};

std::map<std::string, std::string> parse_defines(const std::vector<std::string>& items) {
    std::map<std::string, std::string> defines;
    for (const std::string& item : items) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0) fail("-D expects name=value, got '{}'", item);
        defines[item.substr(0, eq)] = item.substr(eq + 1);
    }
    return defines;
}

void run(const RenderArgs& args) {
    if (args.spp < 0) fail("--spp must be positive, got {}", args.spp);
    if (args.threads < 0) fail("--threads must be positive, got {}", args.threads);
    const std::filesystem::path output(args.output);
    if (output.extension() != ".exr") fail("-o must name an .exr file (the .png is written beside it), got {}", args.output);
    auto scene = render::load_scene(args.scene, parse_defines(args.defines));
    for (const std::string& note : scene->notes) std::fprintf(stderr, "surfscatter: render: %s\n", note.c_str());
    if (args.exposure_set) scene->film.exposure = args.exposure;
    if (!args.white_balance.empty()) scene->film.white_balance = args.white_balance;
    render::RenderOptions options;
    options.spp = args.spp;
    options.threads = args.threads;
    if (args.seed >= 0) options.seed = static_cast<std::uint64_t>(args.seed);
    options.progress = !args.quiet;
    install_interrupt_handler();
    render::RenderStats stats;
    const render::Film film = render::render(*scene, options, &stats);
    if (!output.parent_path().empty()) std::filesystem::create_directories(output.parent_path());
    render::write_film(film, scene->film, output);
    std::fprintf(stderr, "%s: %dx%d, %d spp%s, %.2f s, %.3g Mrays/s -> %s (+ .png)\n", args.scene.c_str(), film.width(),
                 film.height(), stats.samples_per_pixel, stats.interrupted ? " (interrupted)" : "", stats.seconds,
                 static_cast<double>(stats.rays) / std::max(stats.seconds, 1e-9) * 1e-6, args.output.c_str());
}

const Command command("render", [](CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* sub = app.add_subcommand("render", "Render a Mitsuba-3-style XML scene spectrally (EXR + PNG)");
    sub->add_option("scene", args->scene, "Scene file (.xml)")->required();
    sub->add_option("-D", args->defines, "Scene parameter name=value (replaces $name)")->allow_extra_args(false);
    sub->add_option("--spp", args->spp, "Samples per pixel (default: the scene's sampler)");
    sub->add_option("--threads", args->threads, "Worker threads (default: all cores)");
    sub->add_option("--seed", args->seed, "Random seed (default: the scene's sampler seed)");
    sub->add_option("-o,--output", args->output, "Output .exr (the .png goes beside it)");
    sub->add_option("--exposure", args->exposure, "Exposure in stops (overrides the film's)")
        ->each([args](const std::string&) { args->exposure_set = true; });
    sub->add_option("--white-balance", args->white_balance, "d65 (none) or a blackbody temperature in K, e.g. 2700");
    sub->add_flag("--quiet", args->quiet, "No progress bar");
    sub->callback([args] { run(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
