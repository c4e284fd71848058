// surfscatter render: a Mitsuba-style XML scene -> linear sRGB OpenEXR + sRGB PNG; over every rank when started
// by mpirun or srun (distributed/render.hpp), written by rank 0.
#include <cmath>

#include <fmt/format.h>

#include "command.hpp"
#include "scene_defines.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/distributed/render.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/scene_parameters.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::cli {

namespace {

struct RenderArgs {
    std::string scene;
    std::vector<std::string> defines;
    std::optional<int> spp;
    int threads = 0;
    std::optional<long long> seed;
    std::string output;  // default: the scene's name with .exr, beside it (Mitsuba's rule)
    std::optional<double> exposure;
    std::optional<std::string> white_balance;
    bool quiet = false;
};

void run(const RenderArgs& args) {
    distributed::Session session;
    const std::filesystem::path output =
        args.output.empty() ? std::filesystem::path(args.scene).replace_extension(".exr") : std::filesystem::path(args.output);
    const std::filesystem::path png = std::filesystem::path(output).replace_extension(".png");
    std::unique_ptr<render::Scene> scene;
    render::RenderOptions options;
    OutputFiles files;  // rank 0's
    session.collectively([&] {
        if (args.spp && *args.spp <= 0) fail("--spp must be positive, got {}", *args.spp);
        require_thread_count(args.threads, "--threads");
        if (args.seed && *args.seed < 0) fail("--seed must be >= 0, got {}", *args.seed);
        if (output.extension() != ".exr")
            fail("-o must name an .exr file (the .png is written beside it), got {}", printable(output.string()));
        scene = render::load_scene(args.scene, render::implied_scene_parameters(args.scene, parse_defines(args.defines)));
        // The scene's film was checked when it was loaded: what can fail now is the command line's.
        if (args.exposure) {
            scene->film.exposure = *args.exposure;
            if (!(std::abs(*args.exposure) <= render::kMaxExposureStops))
                fail("--exposure must be between -{} and {} stops, got {}", render::kMaxExposureStops,
                     render::kMaxExposureStops, *args.exposure);
        }
        if (args.white_balance) {
            scene->film.white_balance = *args.white_balance;
            try {
                scene->film.check();
            } catch (const Error& e) {
                fail("--white-balance: {}", e.what());
            }
        }
        options.spp = args.spp.value_or(0);
        options.threads = args.threads;
        if (args.seed) options.seed = static_cast<std::uint64_t>(*args.seed);
        options.progress = !args.quiet;
        if (session.root()) {
            if (!output.parent_path().empty()) std::filesystem::create_directories(output.parent_path());
            files.input(args.scene, "scene");
            for (const render::Scene::LoadedFile& file : scene->loaded_files) files.input(file.path, file.named_by);
            files.output(output, "-o");
            files.output(png, "the PNG beside -o");
        }
    });
    if (session.root())
        for (const std::string& note : scene->notes) std::fprintf(stderr, "surfscatter: render: %s\n", note.c_str());
    // Every rank must render the same image for the sum to be the render (mpirun -np 1 a : -np 1 b, or files that
    // differ between hosts, would not).
    session.require_same(fmt::format("{} {}x{} crop {},{} {}x{}, {} spp, seed {}", args.scene, scene->film.width,
                                     scene->film.height, scene->film.crop_offset_x, scene->film.crop_offset_y,
                                     scene->film.output_width(), scene->film.output_height(),
                                     render::samples_per_pixel(*scene, options), options.seed.value_or(scene->sampler.seed)),
                         "the render (scene, film, spp, seed)");
    install_interrupt_handler();
    render::RenderStats stats;
    const render::Film film = distributed::render(session, *scene, options, &stats);
    session.collectively([&] {
        if (!session.root()) return;
        files.write_together({output, png}, [&](const std::vector<std::filesystem::path>& tmp) {
            render::write_film(film, scene->film, tmp[0], tmp[1]);
        });
        files.commit();
    });
    if (!session.root()) return;
    const std::string samples = stats.max_samples_per_pixel > stats.samples_per_pixel
                                    ? fmt::format("{}-{} spp", stats.samples_per_pixel, stats.max_samples_per_pixel)
                                    : fmt::format("{} spp", stats.samples_per_pixel);
    std::fprintf(stderr, "%s: %dx%d, %s%s, %.2f s%s, %.3g Mrays/s; wrote %s and %s\n", printable(args.scene, kShownPathChars).c_str(), film.width(),
                 film.height(), samples.c_str(), stats.interrupted ? " (interrupted)" : "", stats.seconds,
                 session.size() > 1 ? fmt::format(" on {} ranks", session.size()).c_str() : "",
                 static_cast<double>(stats.rays) / std::max(stats.seconds, 1e-9) * 1e-6, printable(output.string(), kShownPathChars).c_str(),
                 printable(png.string(), kShownPathChars).c_str());
    if (const std::string note = render::nonfinite_note(stats); !note.empty())
        std::fprintf(stderr, "warning: %s\n", note.c_str());
}

const Command command("render", [](CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* sub = app.add_subcommand("render", "Render a Mitsuba-3-style XML scene spectrally (EXR + PNG)");
    sub->add_option("scene", args->scene, "Scene file (.xml)")->required();
    sub->add_option("-D", args->defines, "Scene parameter name=value (replaces $name)")->allow_extra_args(false);
    sub->add_option("--spp", args->spp, "Samples per pixel (default: the scene's sampler)");
    sub->add_option("--threads", args->threads, "Worker threads, 1..256 (default 0: all cores)");
    sub->add_option("--seed", args->seed, "Random seed (default: the scene's sampler seed)");
    sub->add_option("-o,--output", args->output, "Output .exr, the .png beside it (default: the scene's name, "
                                                 "scene.xml -> scene.exr + scene.png, as Mitsuba)");
    sub->add_option("--exposure", args->exposure, "Exposure in stops, -64..64 (overrides the film's)");
    sub->add_option("--white-balance", args->white_balance, "d65 (none) or a blackbody temperature in K, e.g. 2700");
    sub->add_flag("--quiet", args->quiet, "No progress bar");
    sub->callback([args] { run(*args); });
});

}  // namespace

}  // namespace surfscatter::cli
