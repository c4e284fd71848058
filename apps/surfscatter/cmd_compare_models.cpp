// surfscatter compare-models: the supplemental's figure set - scenes/photo-setup seen from its views, rendered with
// every scattering model and laid out as one sheet per view - as a preset of `surfscatter study` (same jobs, MPI,
// manifest and resume; the study it runs is written to <output>/study.json).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include <fmt/format.h>

#include "command.hpp"
#include "list_options.hpp"
#include "scene_defines.hpp"
#include "study_runner.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/render/scene.hpp"

namespace surfscatter::cli {

namespace {

struct CompareArgs {
    std::string scene = "scenes/photo-setup/scene.xml";  // relative to the working directory (the repository root)
    std::vector<double> views{1, 2, 3};
    std::vector<std::string> surfaces{"rough", "smooth"};
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

// The supplemental's two KC surfaces, as photo-setup scene parameters (um): the rough one (the scene's default), where
// every model but SSA (first order in g) agrees that the plate is matte, and the smooth one, where they differ.
// "scene" is the scene's own surface with the -D values, one sheet without a surface in its name.
std::vector<study::Variant> supplemental_surfaces(const std::vector<std::string>& names) {
    std::vector<study::Variant> surfaces;
    for (const std::string& name : names) {
        for (const study::Variant& s : surfaces)
            if (s.name == name || (s.name.empty() && name == "scene")) fail("--surfaces names {} twice", name);
        const auto surface = [&](std::string label, std::string sigma, std::string corr_length, std::string gamma) {
            return study::Variant{name, std::move(label),
                                  {{"sigma", std::move(sigma)}, {"corr_length", std::move(corr_length)},
                                   {"gamma", std::move(gamma)}},
                                  "compare-models --surfaces"};
        };
        if (name == "rough") surfaces.push_back(surface("rough KC (sigma 0.15 um, L 4 um, gamma 4)", "0.15", "4", "4"));
        else if (name == "smooth") surfaces.push_back(surface("smooth KC (sigma 0.02 um, L 2 um, gamma 3)", "0.02", "2", "3"));
        else if (name == "scene") surfaces.push_back(study::Variant{});
        else fail("--surfaces: unknown surface '{}' (rough, smooth or scene)", printable(name));
    }
    if (surfaces.empty()) fail("--surfaces needs at least one of rough, smooth, scene");
    if (surfaces.size() > 1)
        for (const study::Variant& s : surfaces)
            if (s.name.empty()) fail("--surfaces scene cannot be combined with the named surfaces (one sheet per view)");
    return surfaces;
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
    s.surfaces = supplemental_surfaces(args.surfaces);
    s.lamps = {study::Variant{}};
    study::RenderSettings r;
    r.spp = args.spp;
    r.width = args.width;
    r.height = args.height;
    // Every render gets the -D parameters; each scene must use them (a job whose scene does not fails, naming it).
    r.parameters = parse_defines(args.defines);
    for (const auto& [name, value] : r.parameters) {
        bool set_by_model = false, set_by_surface = false;
        for (const study::Variant& model : s.models) set_by_model = set_by_model || model.parameters.count(name);
        for (const study::Variant& surface : s.surfaces) set_by_surface = set_by_surface || surface.parameters.count(name);
        if (name == "view" || name == "width" || name == "height" || set_by_model)
            fail("-D {}: compare-models sets this parameter itself (see --view, --width, --height, --smoothing)", name);
        if (set_by_surface)
            fail("-D {}: --surfaces {} sets this parameter (--surfaces scene takes the scene's surface with -D)", name,
                 fmt::join(args.surfaces, ","));
    }
    if (args.focus_radius > 0) {
        r.crop = study::Crop{{args.focus[0], args.focus[1], args.focus[2]}, args.focus_radius};
        r.overview = true;
    }
    s.render = r;
    // GGX (measured) takes alpha from the surface's rms slope, which diverges for a KC gamma <= 3 (the smooth surface's
    // gamma is 3): its renders would fail, so it is left out of every sheet, and the command says so.
    // (A -D gamma that is no number is left to the scene, which names it.)
    std::vector<const study::Parameters*> gammas{&s.render->parameters};
    for (const study::Variant& surface : s.surfaces) gammas.push_back(&surface.parameters);
    const auto at_most_3 = [](const std::string& text) {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        return !text.empty() && *end == '\0' && value <= 3.0;
    };
    for (const study::Parameters* parameters : gammas)
        if (const auto g = parameters->find("gamma"); g != parameters->end() && at_most_3(g->second)) {
            std::erase_if(s.models, [](const study::Variant& m) { return m.name == "ggx_measured"; });
            std::fprintf(stderr,
                         "surfscatter: compare-models: GGX (measured) left out: a surface has KC gamma %s <= 3, where "
                         "the rms slope it takes alpha from diverges (GGX smoothed stands for it)\n",
                         g->second.c_str());
            break;
        }
    return s;
}

const Command command("compare-models", [](CLI::App& app) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* sub = app.add_subcommand(
        "compare-models", "The supplemental's figure set: photo-setup views rendered with GGX (smoothed, measured), SSA "
                          "GHS, GHS and two-scale (50/100/150 lambda), one labelled sheet per view (a study preset)");
    sub->add_option("--scene", args->scene, "Scene with $model, $alpha_from, $smoothing, $cutoff_wavelengths, $view parameters");
    add_number_list(sub, "--view", args->views, "Camera views: 1 (near-normal), 2, 3 (grazing); default 1,2,3");
    add_string_list(sub, "--surfaces", args->surfaces,
                    "Surfaces, one sheet per view each: rough (KC sigma 0.15 um, L 4 um, gamma 4), smooth (sigma 0.02 "
                    "um, L 2 um, gamma 3), or scene (the scene's, with -D); default rough,smooth");
    sub->add_option("-D", args->defines, "Extra scene parameter name=value (e.g. material=Au; sigma=0.2 with --surfaces scene)")->allow_extra_args(false);
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
