// surfscatter compare-models: one view of scenes/photo-setup rendered with every scattering model, as one sheet.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "command.hpp"
#include "list_options.hpp"
#include "scene_defines.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/xml_loader.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::cli {

namespace {

struct CompareArgs {
    std::string scene = "scenes/photo-setup/scene.xml";  // relative to the working directory (the repository root)
    int view = 1;
    std::vector<std::string> defines;
    int spp = 16;
    int width = 1280;   // the full film; only the crop around --focus is rendered
    int height = 960;
    int threads = 0;
    double smoothing = 1.0;
    std::vector<double> focus{0.09, 0.0, 0.001};  // the photo-setup's plate centre, metres
    bool focus_given = false;
    double focus_radius = 0.06;                   // metres; 0 shows whole images
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

struct Box {
    int x0, y0, x1, y1;
};

// Pixel box around the focus point: the projections of the square of half-size focus_radius about it
// in the z = focus plane (the sample lies flat), padded to the film.
Box crop_box(const render::Scene& scene, const CompareArgs& args) {
    const render::Camera camera(scene.camera, scene.film.width, scene.film.height);
    const Vec3 centre(args.focus[0], args.focus[1], args.focus[2]);
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (double dx : {-1.0, 1.0})
        for (double dy : {-1.0, 1.0}) {
            const auto p = camera.project(centre + Vec3(dx, dy, 0) * args.focus_radius);
            if (!p) fail("--focus point ({}, {}, {}) is behind the camera of view {}", args.focus[0], args.focus[1],
                         args.focus[2], args.view);
            x0 = std::min(x0, p->x);
            y0 = std::min(y0, p->y);
            x1 = std::max(x1, p->x);
            y1 = std::max(y1, p->y);
        }
    // Clamped as doubles first: a focus near the camera plane projects to coordinates that no int holds.
    const auto to_pixel = [](double v, int size) {
        return v >= 0 ? (v <= size ? static_cast<int>(std::lround(v)) : size) : 0;
    };
    const auto clampx = [&](double v) { return to_pixel(v, scene.film.width); };
    const auto clampy = [&](double v) { return to_pixel(v, scene.film.height); };
    if (clampx(x1) - clampx(x0) < 8 || clampy(y1) - clampy(y0) < 4) fail("--focus region is outside view {}", args.view);
    return {clampx(x0), clampy(y0), clampx(x1), clampy(y1)};
}

// A low-sample render of the whole view with the crop outlined, as "label=path" for the sheet.
std::string overview(const CompareArgs& args, const std::map<std::string, std::string>& defines,
                     const std::optional<Box>& crop, const std::filesystem::path& dir) {
    // A quarter of the film's resolution is plenty to show where the crop lies.
    constexpr int kReduce = 4;
    std::map<std::string, std::string> d = defines;
    d["model"] = "ggx_stats";
    d["alpha_from"] = "measured";
    d["width"] = std::to_string(std::max(1, args.width / kReduce));
    d["height"] = std::to_string(std::max(1, args.height / kReduce));
    auto scene = render::load_scene(args.scene, d);
    render::RenderOptions options;
    options.spp = std::max(1, args.spp / 2);
    options.threads = args.threads;
    options.progress = !args.quiet;
    const render::Film film = render::render(*scene, options);
    io::Image image = film.develop(scene->film);
    for (float& v : image.pixels) v = static_cast<float>(spectrum::srgb_encode(static_cast<double>(v)));
    if (crop) {  // a red outline, 2 pixels wide
        auto paint = [&](int x, int y) {
            if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
            image.at(x, y, 0) = 1.0f;
            image.at(x, y, 1) = image.at(x, y, 2) = 0.0f;
        };
        const Box b{crop->x0 / kReduce, crop->y0 / kReduce, crop->x1 / kReduce, crop->y1 / kReduce};
        for (int t = 0; t < 2; ++t) {
            for (int x = b.x0; x < b.x1; ++x) {
                paint(x, b.y0 + t);
                paint(x, b.y1 - 1 - t);
            }
            for (int y = b.y0; y < b.y1; ++y) {
                paint(b.x0 + t, y);
                paint(b.x1 - 1 - t, y);
            }
        }
    }
    const std::filesystem::path path = dir / "overview.png";
    io::write_png(path, image);
    return "whole view=" + path.string();
}

void run(const CompareArgs& args) {
    if (args.view < 1 || args.view > 3) fail("--view must be 1, 2 or 3, got {}", args.view);
    if (args.spp < 1) fail("--spp must be positive, got {}", args.spp);
    if (args.width < 1 || args.height < 1) fail("--width and --height must be positive, got {}x{}", args.width, args.height);
    require_thread_count(args.threads, "--threads");
    require_positive(args.smoothing, "--smoothing");
    require_non_negative(args.focus_radius, "--focus-radius");
    if (args.focus.size() != 3) fail("--focus needs x,y,z, got {} numbers", args.focus.size());
    for (double v : args.focus)
        if (!(std::abs(v) <= render::kMaxSceneCoordinate))
            fail("--focus coordinates must be within +-{:g} m, got {}", render::kMaxSceneCoordinate, v);
    if (!(args.focus_radius <= render::kMaxSceneCoordinate))
        fail("--focus-radius must be at most {:g} m, got {}", render::kMaxSceneCoordinate, args.focus_radius);
    if (args.focus_given && args.focus_radius == 0) fail("--focus does not apply with --focus-radius 0 (whole images)");
    const std::map<std::string, std::string> user = parse_defines(args.defines);
    std::map<std::string, std::string> common = user;
    common["view"] = std::to_string(args.view);
    common["width"] = std::to_string(args.width);
    common["height"] = std::to_string(args.height);
    const auto list = panels(args.smoothing);
    for (const auto& [name, value] : user) {
        const bool set_by_panel = std::any_of(list.begin(), list.end(), [&](const Panel& p) { return p.defines.count(name); });
        if (name == "view" || name == "width" || name == "height" || set_by_panel)
            fail("-D {}: compare-models sets this parameter itself (see --view, --width, --height, --smoothing)", name);
    }

    // Every panel's scene is loaded before anything is rendered: a bad parameter is reported at once, and each -D
    // is checked against all the scenes together (a parameter only some models use is fine).
    std::set<std::string> used;
    std::vector<std::unique_ptr<render::Scene>> scenes;
    for (const Panel& panel : list) {
        std::map<std::string, std::string> defines = common;
        for (const auto& [k, v] : panel.defines) defines[k] = v;
        scenes.push_back(render::load_scene(args.scene, defines, &used));
    }
    for (const auto& [name, value] : user)
        if (!used.count(name)) fail("-D {}={}: none of the scenes uses ${}", name, printable(value), name);
    const std::filesystem::path dir(args.output_dir);
    std::filesystem::create_directories(dir);
    install_interrupt_handler();

    std::vector<std::string> sheet_args;
    std::optional<Box> crop;
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Panel& panel = list[i];
        render::Scene* scene = scenes[i].get();
        // Only the crop around the sample is rendered (Mitsuba's film crop window), at the full film's resolution.
        if (i == 0 && args.focus_radius > 0) crop = crop_box(*scene, args);
        if (crop) {
            scene->film.crop_offset_x = crop->x0;
            scene->film.crop_offset_y = crop->y0;
            scene->film.crop_width = crop->x1 - crop->x0;
            scene->film.crop_height = crop->y1 - crop->y0;
        }
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
        scenes[i].reset();
        if (stats.interrupted) break;
    }
    // Two rows as in the supplemental: the four models of Figs. 3/5/7, then the two-scale cutoffs of Figs. 4/6/8,
    // with the whole view (where the crop comes from) first in the second row.
    if (sheet_args.size() > 4) sheet_args.insert(sheet_args.begin() + 4, overview(args, common, crop, dir));
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
    sub->add_option("--threads", args->threads, "Worker threads, 1..256 (default 0: all cores)");
    sub->add_option("--smoothing", args->smoothing, "Gaussian smoothing std for the smoothed GGX, um");
    add_number_list(sub, "--focus", args->focus, "World point (x,y,z, metres) the sheet's panels are cropped around");
    sub->add_option("--focus-radius", args->focus_radius, "Half-size of the cropped square, metres (0: whole images)");
    sub->add_option("-o,--output-dir", args->output_dir, "Directory for the renders (EXR + PNG) and sheet.png");
    sub->add_flag("--quiet", args->quiet, "No progress bars");
    sub->callback([args, sub] {
        args->focus_given = sub->count("--focus") > 0;
        run(*args);
    });
});

}  // namespace

}  // namespace surfscatter::cli
