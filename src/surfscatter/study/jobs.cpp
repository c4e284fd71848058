#include "surfscatter/study/jobs.hpp"

#include <map>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/study/sheet_caption.hpp"

namespace surfscatter::study {

namespace {

using nlohmann::json;

// "a/b/c" from the non-empty parts.
std::string join(std::initializer_list<std::string> parts, const char* separator) {
    std::string out;
    for (const std::string& p : parts) {
        if (p.empty()) continue;
        if (!out.empty()) out += separator;
        out += p;
    }
    return out;
}

std::string wavelength_name(double nm) { return fmt::format("{}nm", nm); }

// Later maps win.
Parameters merged(std::initializer_list<const Parameters*> maps) {
    Parameters out;
    for (const Parameters* m : maps)
        for (const auto& [k, v] : *m) out[k] = v;
    return out;
}

// Every file a job's parameters may name: each text value taken as a path against the study's folder and against
// the scene's (where the scene resolves its -D values); OutputFiles::input passes over those that name nothing.
void declare_parameter_files(OutputFiles& files, const Study& s, const json& parameters, const std::string& id) {
    if (parameters.is_object() || parameters.is_array()) {
        for (const json& value : parameters) declare_parameter_files(files, s, value, id);
        return;
    }
    if (!parameters.is_string()) return;
    const std::string value = parameters.get<std::string>();
    const std::string what = fmt::format("'{}' of job {}", printable(value), id);
    files.input(s.resolve(value), what);
    if (s.render) files.input(s.resolve(s.scene).parent_path() / value, what);
}

// A job's outputs never replace a file the study loads (its scene, maps, materials, profiles) or another job's
// output (core/output_files.hpp's rule), checked before any job runs: a model named "overview" wrote over the
// view's overview, and surface "a_b" with lamp "c" over surface "a" with lamp "b_c"'s sheet.
void refuse_output_collisions(const Study& s, const std::vector<Job>& jobs) {
    OutputFiles files;
    if (s.render) files.input(s.resolve(s.scene), "the study's scene");
    for (const Job& job : jobs)  // sheets and plots name only other jobs' outputs (and titles)
        if (job.kind != JobKind::sheet && job.kind != JobKind::slice_plot && job.kind != JobKind::albedo_plot)
            declare_parameter_files(files, s, job.parameters, job.id);
    for (const Job& job : jobs)
        for (const std::string& output : job.outputs) files.plan(s.folder / output, fmt::format("job {}'s output", job.id));
}

class Expander {
public:
    explicit Expander(const Study& study) : s_(study) {}

    std::vector<Job> expand() {
        if (s_.render && !std::filesystem::exists(s_.resolve(s_.scene)))
            fail("{}: scene file not found: {}", s_.origin, s_.resolve(s_.scene).string());
        // Tables first: one per (surface, model) pair with more than one job, so that they are built once.
        for (const Variant& surface : s_.surfaces)
            for (const Variant& model : s_.models) add_tables(surface, model);
        if (s_.render) add_renders();
        for (const Variant& surface : s_.surfaces)
            for (const double wl : s_.wavelengths) {
                if (s_.slices) add_brdf_jobs(JobKind::slice, surface, wl, *s_.slices);
                if (s_.albedo) add_brdf_jobs(JobKind::albedo, surface, wl, *s_.albedo);
            }
        // Sheets and plots last: they wait for everything they show.
        for (Job& j : deferred_) add(std::move(j));
        // Tables that only one job needs are dropped: that job builds them itself.
        std::vector<Job> jobs;
        std::vector<int> index(jobs_.size(), -1);
        std::vector<int> users(jobs_.size(), 0);
        for (const Job& j : jobs_)
            for (const int d : j.dependencies) ++users[static_cast<std::size_t>(d)];
        for (std::size_t i = 0; i < jobs_.size(); ++i) {
            if (jobs_[i].kind == JobKind::tables && users[i] < 2) continue;
            Job j = jobs_[i];
            std::vector<int> deps;
            for (const int d : j.dependencies)
                if (index[static_cast<std::size_t>(d)] >= 0) deps.push_back(index[static_cast<std::size_t>(d)]);
            j.dependencies = std::move(deps);
            index[i] = static_cast<int>(jobs.size());
            jobs.push_back(std::move(j));
        }
        refuse_output_collisions(s_, jobs);
        return jobs;
    }

private:
    int add(Job job) {
        jobs_.push_back(std::move(job));
        return static_cast<int>(jobs_.size()) - 1;
    }

    // The parameters of a BRDF job (and of a tables job without renders): study-wide, surface, model.
    Parameters model_parameters(const Variant& surface, const Variant& model) const {
        return s_.with_absolute_files(merged({&s_.parameters, &surface.parameters, &model.parameters}));
    }

    // The scene parameters of one render.
    Parameters scene_parameters(const Variant& surface, const Variant& lamp, const Variant& model,
                                const std::string& view) const {
        Parameters p = merged({&s_.parameters, &surface.parameters, &lamp.parameters, &model.parameters,
                               &s_.render->parameters});
        p["view"] = view;
        if (s_.render->width) p["width"] = std::to_string(s_.render->width);
        if (s_.render->height) p["height"] = std::to_string(s_.render->height);
        return s_.with_absolute_files(p);
    }

    json render_parameters(const Parameters& defines, int spp) const {
        json p = {{"scene", s_.scene}, {"defines", defines}, {"spp", spp}, {"seed", nullptr}, {"crop", nullptr}};
        if (s_.render->seed) p["seed"] = *s_.render->seed;
        if (s_.render->crop) p["crop"] = {{"focus", s_.render->crop->focus}, {"radius", s_.render->crop->radius}};
        return p;
    }

    void add_tables(const Variant& surface, const Variant& model) {
        Job j;
        j.kind = JobKind::tables;
        j.id = "tables/" + join({surface.name, model.name}, "/");
        if (s_.render)
            j.parameters = {{"scene", s_.scene},
                            {"defines", scene_parameters(surface, s_.lamps.front(), model, s_.views.front())}};
        else
            j.parameters = {{"model_options", model_parameters(surface, model)}};
        tables_[{surface.name, model.name}] = add(std::move(j));
    }

    std::vector<int> tables_of(const Variant& surface, const Variant& model) const {
        return {tables_.at({surface.name, model.name})};
    }

    void add_renders() {
        const RenderSettings& r = *s_.render;
        for (const Variant& surface : s_.surfaces)
            for (const Variant& lamp : s_.lamps)
                for (const std::string& view : s_.views) {
                    const std::string where = join({surface.name, lamp.name, "view" + view}, "/");
                    // Each panel is captioned with its label, its surface and roughness, and a warning where its model
                    // is outside its validity (sheet_caption.hpp); sheet_compare.py draws lines starting with '!'
                    // as warnings.
                    std::vector<std::pair<std::string, std::string>> panels;  // caption, path
                    std::vector<int> panel_jobs;
                    const int columns = sheet_columns(s_.models.size() + (r.overview ? 1 : 0), r.columns);
                    for (const Variant& model : s_.models) {
                        Job j;
                        j.kind = JobKind::render;
                        j.id = "render/" + where + "/" + model.name;
                        const Parameters defines = scene_parameters(surface, lamp, model, view);
                        j.parameters = render_parameters(defines, r.spp);
                        const std::string stem = "renders/" + where + "/" + model.name;
                        j.outputs = {stem + ".exr", stem + ".png"};
                        j.dependencies = tables_of(surface, model);
                        const PanelCaption caption = panel_caption(defines, s_.resolve(s_.scene));
                        std::string text = model.label;
                        if (!caption.surface.empty()) text += "\n" + caption.surface;
                        if (!caption.warning.empty()) text += "\n!" + caption.warning;
                        panels.emplace_back(text, stem + ".png");
                        panel_jobs.push_back(add(std::move(j)));
                    }
                    if (r.overview) {
                        // The whole view at a quarter of the resolution and half the samples, with the first model.
                        Job j;
                        j.kind = JobKind::overview;
                        j.id = "overview/" + where;
                        j.parameters = render_parameters(
                            scene_parameters(surface, lamp, s_.models.front(), view), std::max(1, r.spp / 2));
                        j.parameters["reduce"] = 4;
                        j.outputs = {"renders/" + where + "/overview.png"};
                        j.dependencies = tables_of(surface, s_.models.front());
                        // As in the supplemental: the overview opens the second row.
                        const auto at = panels.begin() + std::min<std::ptrdiff_t>(columns, static_cast<std::ptrdiff_t>(panels.size()));
                        panels.insert(at, {"whole view", j.outputs.front()});
                        panel_jobs.push_back(add(std::move(j)));
                    }
                    Job sheet;
                    sheet.kind = JobKind::sheet;
                    sheet.id = "sheet/" + where;
                    const std::filesystem::path scene_path(s_.scene);
                    const std::string scene_name = scene_path.parent_path().filename().string().empty()
                                                       ? scene_path.stem().string()
                                                       : scene_path.parent_path().filename().string();
                    std::string title = fmt::format("{} view {}", scene_name, view);
                    if (!surface.name.empty()) title += ", " + surface.label;
                    if (!lamp.name.empty()) title += ", " + lamp.label;
                    title += fmt::format(", {} spp", r.spp);
                    json list = json::array();
                    for (const auto& [label, path] : panels) {
                        list.push_back({label, path});
                        sheet.inputs.push_back(path);
                    }
                    // Without a crop the panels are cropped to where the models differ: the sample.
                    sheet.parameters = {{"title", title}, {"columns", columns}, {"panels", list},
                                        {"crop_to_difference", !r.crop && s_.models.size() > 1}};
                    sheet.outputs = {"sheets/" + join({surface.name, lamp.name, "view" + view}, "_") + ".png"};
                    sheet.dependencies = panel_jobs;
                    deferred_.push_back(std::move(sheet));
                }
    }

    void add_brdf_jobs(JobKind kind, const Variant& surface, double wavelength, const AngleSettings& angles) {
        const char* what = kind == JobKind::slice ? "slice" : "albedo";
        const std::string folder = join({"brdf", surface.name}, "/");
        const std::string where = join({surface.name, wavelength_name(wavelength)}, "/");
        Job plot;
        plot.kind = kind == JobKind::slice ? JobKind::slice_plot : JobKind::albedo_plot;
        plot.id = fmt::format("{}-plot/{}", what, where);
        for (const Variant& model : s_.models) {
            Job j;
            j.kind = kind;
            j.id = fmt::format("{}/{}/{}", what, where, model.name);
            j.parameters = {{"model_options", model_parameters(surface, model)},
                            {"name", model.name},
                            {"wavelength", wavelength},
                            {"theta_i", angles.theta_i},
                            {"phi_i", angles.phi_i}};
            j.outputs = {fmt::format("{}/{}_{}_{}.csv", folder, what, wavelength_name(wavelength), model.name)};
            j.dependencies = tables_of(surface, model);
            plot.inputs.push_back(j.outputs.front());
            plot.dependencies.push_back(add(std::move(j)));
        }
        std::string title = fmt::format("{} nm", wavelength);
        if (!surface.name.empty()) title = surface.label + ", " + title;
        json labels = json::object();
        for (const Variant& model : s_.models) labels[model.name] = model.label;
        plot.parameters = {{"title", title}, {"parts", plot.inputs}, {"labels", labels}};
        const std::string stem = fmt::format("{}/{}_{}", folder, what, wavelength_name(wavelength));
        plot.outputs = {stem + ".csv", stem + ".png"};
        deferred_.push_back(std::move(plot));
    }

    const Study& s_;
    std::vector<Job> jobs_;
    std::vector<Job> deferred_;
    std::map<std::pair<std::string, std::string>, int> tables_;
};

}  // namespace

const char* to_string(JobKind kind) {
    switch (kind) {
        case JobKind::tables: return "tables";
        case JobKind::render: return "render";
        case JobKind::overview: return "overview";
        case JobKind::slice: return "slice";
        case JobKind::albedo: return "albedo";
        case JobKind::sheet: return "sheet";
        case JobKind::slice_plot: return "slice-plot";
        case JobKind::albedo_plot: return "albedo-plot";
    }
    return "?";
}

std::vector<Job> expand(const Study& study) { return Expander(study).expand(); }

}  // namespace surfscatter::study
