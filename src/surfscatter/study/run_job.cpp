#include "surfscatter/study/run_job.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/slice.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/model_parameters.hpp"
#include "surfscatter/render/scene_parameters.hpp"
#include "surfscatter/render/xml_loader.hpp"
#include "surfscatter/spectrum/color.hpp"
#include "surfscatter/study/manifest.hpp"

namespace surfscatter::study {

namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// This process's CPU time and that of the children it waited for (the plotting scripts of sheets and plots).
double cpu_seconds() {
    const auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    double total = 0;
    for (const int who : {RUSAGE_SELF, RUSAGE_CHILDREN}) {
        rusage usage{};
        getrusage(who, &usage);
        total += seconds(usage.ru_utime) + seconds(usage.ru_stime);
    }
    return total;
}

struct Box {
    int x0, y0, x1, y1;
};

// Pixel box of the full film around crop.focus: the projections of the square of half-size radius about it in its
// z plane (a sample lying flat), clamped to the film.
Box crop_box(const render::Scene& scene, int width, int height, const json& crop) {
    const render::Camera camera(scene.camera, width, height);
    const Vec3 centre(crop["focus"][0].get<double>(), crop["focus"][1].get<double>(), crop["focus"][2].get<double>());
    const double radius = crop["radius"].get<double>();
    double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
    for (double dx : {-1.0, 1.0})
        for (double dy : {-1.0, 1.0}) {
            const auto p = camera.project(centre + Vec3(dx, dy, 0) * radius);
            if (!p) fail("the crop's focus point is behind the camera");
            x0 = std::min(x0, p->x);
            y0 = std::min(y0, p->y);
            x1 = std::max(x1, p->x);
            y1 = std::max(y1, p->y);
        }
    // Clamped as doubles first: a focus near the camera plane projects to coordinates that no int holds.
    const auto clamp_to = [](double v, int size) { return v >= 0 ? (v <= size ? static_cast<int>(std::lround(v)) : size) : 0; };
    const Box box{clamp_to(x0, width), clamp_to(y0, height), clamp_to(x1, width), clamp_to(y1, height)};
    if (box.x1 - box.x0 < 8 || box.y1 - box.y0 < 4) fail("the crop around the focus point is outside the view");
    return box;
}

class Runner {
public:
    Runner(const Study& study, const Job& job, const JobContext& context) : s_(study), job_(job), context_(context) {}

    json run() {
        const auto start = std::chrono::steady_clock::now();
        const double cpu_start = cpu_seconds();
        json report = {{"status", "done"}, {"host", context_.host}};
        try {
            switch (job_.kind) {
                case JobKind::tables: tables(); break;
                case JobKind::render: render(); break;
                case JobKind::overview: overview(); break;
                case JobKind::slice:
                case JobKind::albedo: brdf_table(); break;
                case JobKind::sheet: sheet(); break;
                case JobKind::slice_plot:
                case JobKind::albedo_plot: plot(); break;
            }
            if (interrupted_) report["status"] = "interrupted";
        } catch (...) {
            report["status"] = "failed";
            report["error"] = error_message(std::current_exception());
            // Outputs of earlier runs (with other parameters) must not pass for this job's on sheets and plots.
            std::error_code ec;
            for (const std::string& path : job_.outputs) {
                fs::remove(s_.folder / path, ec);
            }
        }
        json outputs = json::array(), inputs = json::array();
        for (const std::string& path : job_.outputs)
            if (const auto f = fingerprint(s_.folder / path))
                outputs.push_back({{"path", path}, {"bytes", f->bytes}, {"fnv1a", f->fnv1a}});
        for (const std::string& path : job_.inputs)
            if (const auto f = fingerprint(s_.folder / path)) inputs.push_back({{"path", path}, {"fnv1a", f->fnv1a}});
        report["outputs"] = outputs;
        if (!job_.inputs.empty()) report["inputs"] = inputs;
        if (!notes_.empty()) report["notes"] = notes_;
        report["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        report["cpu_seconds"] = cpu_seconds() - cpu_start;
        return report;
    }

private:
    fs::path output(std::size_t i) const { return s_.folder / job_.outputs.at(i); }

    // Writes the job's outputs `paths` (core/output_files.hpp) through `write(their temporary paths)`.
    template <typename Write>
    void write_outputs(const std::vector<fs::path>& paths, Write&& write) {
        OutputFiles files;
        for (const auto& [path, what] : inputs_) files.input(path, what);
        for (const fs::path& path : paths) {
            fs::create_directories(path.parent_path());
            files.output(path, "the study's output");
        }
        files.write_together(paths, write);
        files.commit();
    }

    std::unique_ptr<render::Scene> load(const json& defines_json) {
        const fs::path path = s_.resolve(job_.parameters["scene"].get<std::string>());
        auto scene = render::load_scene(path, render::implied_scene_parameters(path, defines_json.get<Parameters>()));
        for (const std::string& note : scene->notes) notes_.push_back(note);
        // What the scene loads (meshes, textures, maps, index tables, through -D values too) its outputs must not
        // replace; the study's expansion checked the files its parameters name.
        inputs_.emplace_back(path, "the study's scene");
        for (const render::Scene::LoadedFile& file : scene->loaded_files) inputs_.emplace_back(file.path, file.named_by);
        return scene;
    }

    render::Film render_scene(const render::Scene& scene, int spp) {
        render::RenderOptions options;
        options.spp = spp;
        options.threads = context_.threads;
        options.progress = context_.progress;
        if (!job_.parameters["seed"].is_null()) options.seed = job_.parameters["seed"].get<std::uint64_t>();
        render::RenderStats stats;
        render::Film film = render::render(scene, options, &stats);
        interrupted_ = interrupted_ || stats.interrupted;
        if (stats.interrupted) notes_.push_back(fmt::format("interrupted after {} of {} spp", stats.samples_per_pixel, spp));
        if (const std::string note = render::nonfinite_note(stats); !note.empty()) notes_.push_back(note);
        return film;
    }

    // The job's model parameters as the model's options (the "model" parameter is the plugin type) and the model.
    std::unique_ptr<bsdf::Bsdf> make_model() {
        auto parameters = job_.parameters["model_options"].get<std::map<std::string, std::string>>();
        const auto type = parameters.find("model");
        if (type == parameters.end()) fail("model parameters: no \"model\" (ghs, ghs_ssa, ggx_stats, two_scale)");
        const std::string model = type->second;
        parameters.erase(type);
        const bsdf::ModelOptions options = render::scattering_model_options(model, parameters, "model parameters", &notes_);
        return bsdf::make_bsdf(options, &notes_);
    }

    void tables() {
        if (job_.parameters.contains("scene")) load(job_.parameters["defines"]);  // building the scene builds its BSDFs
        else make_model();
    }

    void render() {
        const auto scene = load(job_.parameters["defines"]);
        if (!job_.parameters["crop"].is_null()) {
            // Only the crop around the sample is rendered (Mitsuba's film crop window), at the film's resolution.
            const Box b = crop_box(*scene, scene->film.width, scene->film.height, job_.parameters["crop"]);
            scene->film.crop_offset_x = b.x0;
            scene->film.crop_offset_y = b.y0;
            scene->film.crop_width = b.x1 - b.x0;
            scene->film.crop_height = b.y1 - b.y0;
        }
        const render::Film film = render_scene(*scene, job_.parameters["spp"].get<int>());
        fs::path png = output(0);
        png.replace_extension(".png");
        write_outputs({output(0), png}, [&](const std::vector<fs::path>& tmp) { render::write_film(film, scene->film, tmp[0], tmp[1]); });
    }

    void overview() {
        json defines = job_.parameters["defines"];
        const int reduce = job_.parameters["reduce"].get<int>();
        // The crop is where the full-resolution renders put it; the view itself is rendered at 1/reduce of it.
        int width = 0, height = 0;
        {
            const auto full = load(defines);
            width = full->film.width;
            height = full->film.height;
        }
        defines["width"] = std::to_string(std::max(1, width / reduce));
        defines["height"] = std::to_string(std::max(1, height / reduce));
        const auto scene = load(defines);
        const Box crop = crop_box(*scene, width, height, job_.parameters["crop"]);
        const render::Film film = render_scene(*scene, job_.parameters["spp"].get<int>());
        io::Image image = film.develop(scene->film);
        for (float& v : image.pixels) v = static_cast<float>(spectrum::srgb_encode(std::clamp(static_cast<double>(v), 0.0, 1.0)));
        const auto paint = [&](int x, int y) {  // red
            if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
            image.at(x, y, 0) = 1.0f;
            image.at(x, y, 1) = image.at(x, y, 2) = 0.0f;
        };
        const Box b{crop.x0 / reduce, crop.y0 / reduce, crop.x1 / reduce, crop.y1 / reduce};
        for (int t = 0; t < 2; ++t) {  // an outline 2 pixels wide
            for (int x = b.x0; x < b.x1; ++x) {
                paint(x, b.y0 + t);
                paint(x, b.y1 - 1 - t);
            }
            for (int y = b.y0; y < b.y1; ++y) {
                paint(b.x0 + t, y);
                paint(b.x1 - 1 - t, y);
            }
        }
        write_outputs({output(0)}, [&](const std::vector<fs::path>& tmp) { io::write_png(tmp[0], image); });
    }

    void brdf_table() {
        const auto model = make_model();
        const auto& p = job_.parameters;
        const auto theta_i = p["theta_i"].get<std::vector<double>>();
        std::ostringstream text;
        if (job_.kind == JobKind::slice)
            bsdf::write_slice_csv(text, p["name"], *model, theta_i, p["phi_i"].get<double>(), p["wavelength"].get<double>(), true);
        else
            bsdf::write_albedo_csv(text, p["name"], *model, theta_i, bsdf::albedo_azimuths(*model, p["phi_i"].get<double>()),
                                   p["wavelength"].get<double>(), true);
        write_outputs({output(0)}, [&](const std::vector<fs::path>& tmp) { write_file_atomically(tmp[0], text.str()); });
    }

    // A failed render leaves no image (run() removes it): its panel stays empty, captioned as missing.
    void sheet() {
        const auto& p = job_.parameters;
        std::vector<std::string> panels;
        std::size_t missing = 0;
        for (const json& panel : p["panels"]) {
            const fs::path path = s_.folder / panel[1].get<std::string>();
            if (!fs::exists(path)) {
                notes_.push_back(fmt::format("{} is missing from the sheet", panel[1].get<std::string>()));
                ++missing;
            }
            panels.push_back(panel[0].get<std::string>() + "=" + path.string());
        }
        if (missing == panels.size()) fail("none of the sheet's images exists (their jobs failed)");
        write_outputs({output(0)}, [&](const std::vector<fs::path>& tmp) {
            std::vector<std::string> args = {tmp[0].string(), p["title"].get<std::string>(), std::to_string(p["columns"].get<int>())};
            if (p.value("crop_to_difference", false)) args.push_back("--crop-to-difference");
            args.insert(args.end(), panels.begin(), panels.end());
            run_plot_script("sheet_compare.py", args);
        });
    }

    // The models' tables of one surface and wavelength in one CSV, and their plot.
    void plot() {
        std::string text;
        for (const json& part : job_.parameters["parts"]) {
            std::ifstream in(s_.folder / part.get<std::string>());
            if (!in) {  // its job failed
                notes_.push_back(fmt::format("{} is missing from the plot", part.get<std::string>()));
                continue;
            }
            std::string line;
            for (bool first = true; std::getline(in, line); first = false)
                if (!first || text.empty()) text += line + "\n";
        }
        if (text.empty()) fail("none of the models' tables exists (their jobs failed)");
        const char* script = job_.kind == JobKind::slice_plot ? "brdf_slice.py" : "albedo_curves.py";
        write_outputs({output(0), output(1)}, [&](const std::vector<fs::path>& tmp) {
            write_file_atomically(tmp[0], text);
            std::vector<std::string> args{tmp[0].string(), tmp[1].string(), job_.parameters["title"].get<std::string>()};
            const json labels = job_.parameters.value("labels", json::object());  // kept: items() refers to it
            for (const auto& [name, label] : labels.items())
                args.push_back(name + "=" + label.get<std::string>());  // legends show the study's labels
            run_plot_script(script, args);
        });
    }

    const Study& s_;
    const Job& job_;
    const JobContext& context_;
    bool interrupted_ = false;
    std::vector<std::string> notes_;
    std::vector<std::pair<fs::path, std::string>> inputs_;  // files the job loaded, named as their loader names them
};

}  // namespace

json run_job(const Study& study, const Job& job, const JobContext& context) { return Runner(study, job, context).run(); }

}  // namespace surfscatter::study
