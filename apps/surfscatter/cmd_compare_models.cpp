// surfscatter compare-models: the supplemental's figure set - scenes/photo-setup seen from its views, rendered with
// every scattering model and laid out as one sheet per view - as a preset of `surfscatter study` (same jobs, MPI,
// manifest and resume; the study it runs is written to <output>/study.json).
#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include "command.hpp"
#include "list_options.hpp"
#include "scene_defines.hpp"
#include "study_runner.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::cli {

namespace {

struct CompareArgs {
    std::string scene = "scenes/photo-setup/scene.xml";  // relative to the working directory (the repository root)
    std::vector<double> views{1, 2, 3};
    std::vector<std::string> defines;
    int spp = 16;
    int width = 1280;   // the full film; only the crop around --focus is rendered
    int height = 960;
    double smoothing = 1.0;
    std::vector<double> focus{0.09, 0.0, 0.001};  // the photo-setup's plate centre, metres
    bool focus_given = false;
    double focus_radius = 0.06;                   // metres; 0 shows whole images
    std::string output_dir = "out/compare-models";
    StudyRunOptions run;
};

// The models of the supplemental: Figures 3/5/7 (GGX smoothed and measured, SSA GHS, full GHS) and 4/6/8
// (two-scale at 50, 100 and 150 wavelengths), as photo-setup scene parameters.
std::vector<study::Variant> supplemental_models(double smoothing) {
    const auto model = [](std::string name, std::string label, study::Parameters parameters) {
        return study::Variant{std::move(name), std::move(label), std::move(parameters), "compare-models"};
    };
    return {
        model("ggx_smoothed", fmt::format("GGX (smoothed {} um)", smoothing),
              {{"model", "ggx_stats"}, {"alpha_from", "smoothed"}, {"smoothing", fmt::format("{}", smoothing)}}),
        model("ggx_measured", "GGX (measured)", {{"model", "ggx_stats"}, {"alpha_from", "measured"}}),
        model("ghs_ssa", "SSA GHS", {{"model", "ghs_ssa"}}),
        model("ghs", "GHS", {{"model", "ghs"}}),
        model("two_scale_50", "two-scale 50 lambda", {{"model", "two_scale"}, {"cutoff_wavelengths", "50"}}),
        model("two_scale_100", "two-scale 100 lambda", {{"model", "two_scale"}, {"cutoff_wavelengths", "100"}}),
        model("two_scale_150", "two-scale 150 lambda", {{"model", "two_scale"}, {"cutoff_wavelengths", "150"}}),
    };
}

study::Study preset(const CompareArgs& args) {
    for (const double v : args.views)
        if (v != 1 && v != 2 && v != 3) fail("--view must be 1, 2 or 3, got {}", v);
    if (args.spp < 1) fail("--spp must be positive, got {}", args.spp);
    if (args.width < 1 || args.height < 1) fail("--width and --height must be positive, got {}x{}", args.width, args.height);
    require_positive(args.smoothing, "--smoothing");
    require_non_negative(args.focus_radius, "--focus-radius");
    if (args.focus.size() != 3) fail("--focus needs x,y,z, got {} numbers", args.focus.size());
    for (double v : args.focus)
        if (!(std::abs(v) <= render::kMaxSceneCoordinate))
            fail("--focus coordinates must be within +-{:g} m, got {}", render::kMaxSceneCoordinate, v);
    if (!(args.focus_radius <= render::kMaxSceneCoordinate))
        fail("--focus-radius must be at most {:g} m, got {}", render::kMaxSceneCoordinate, args.focus_radius);
    if (args.focus_given && args.focus_radius == 0) fail("--focus does not apply with --focus-radius 0 (whole images)");
    study::Study s;
    s.origin = "compare-models";
    s.base = std::filesystem::current_path();
    s.folder = args.output_dir;
    s.scene = args.scene;
    for (const double v : args.views) s.views.push_back(fmt::format("{}", v));
    s.models = supplemental_models(args.smoothing);
    s.surfaces = {study::Variant{}};
    s.lamps = {study::Variant{}};
    study::RenderSettings r;
    r.spp = args.spp;
    r.width = args.width;
    r.height = args.height;
    // Every render gets the -D parameters; each scene must use them (a job whose scene does not fails, naming it).
    r.parameters = parse_defines(args.defines);
    for (const auto& [name, value] : r.parameters) {
        bool set_by_model = false;
        for (const study::Variant& model : s.models) set_by_model = set_by_model || model.parameters.count(name);
        if (name == "view" || name == "width" || name == "height" || set_by_model)
            fail("-D {}: compare-models sets this parameter itself (see --view, --width, --height, --smoothing)", name);
    }
    if (args.focus_radius > 0) {
        r.crop = study::Crop{{args.focus[0], args.focus[1], args.focus[2]}, args.focus_radius};
        r.overview = true;
    }
    s.render = r;
    return s;
}

const Command command("compare-models", [](CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand(
        "compare-models", "The supplemental's figure set: photo-setup views rendered with GGX (smoothed, measured), SSA "
                          "GHS, GHS and two-scale (50/100/150 lambda), one labelled sheet per view (a study preset)");
    sub->add_option("--scene", args->scene, "Scene with $model, $alpha_from, $smoothing, $cutoff_wavelengths, $view parameters");
    add_number_list(sub, "--view", args->views, "Camera views: 1 (near-normal), 2, 3 (grazing); default 1,2,3");
    sub->add_option("-D", args->defines, "Extra scene parameter name=value (e.g. sigma=0.2)")->allow_extra_args(false);
    sub->add_option("--spp", args->spp, "Samples per pixel");
    sub->add_option("--width", args->width, "Image width");
    sub->add_option("--height", args->height, "Image height");
    sub->add_option("--smoothing", args->smoothing, "Gaussian smoothing std for the smoothed GGX, um");
    add_number_list(sub, "--focus", args->focus, "World point (x,y,z, metres) the sheet's panels are cropped around");
    sub->add_option("--focus-radius", args->focus_radius,
                    "Half-size of the cropped square, metres (0: whole images, the sheet's panels cropped to where the "
                    "models differ)");
    sub->add_option("-o,--output-dir", args->output_dir, "Folder for the renders, sheets/, manifest.json, study.json");
    add_study_run_options(sub, args->run);
    sub->callback([args, sub] {
        args->focus_given = sub->count("--focus") > 0;
        run_study(
            [&] {
                study::Study s = preset(*args);
                // The same study as a file, for `surfscatter study` (e.g. to add surfaces or lamps).
                std::filesystem::create_directories(s.folder);
                write_file_atomically(s.folder / "study.json", study::to_json(s));
                return s;
            },
            args->run);
    });
});

}  // namespace

}  // namespace surfscatter::cli
