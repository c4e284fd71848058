#pragma once
// A study: renders, BRDF slices and albedo tables of several scattering models over views, surfaces, lamps and
// wavelengths, described by one JSON file (format in docs/DISTRIBUTED.md, "Study files") and expanded into
// independent jobs (jobs.hpp) that `surfscatter study` runs on one machine or over MPI ranks.
//
// Parameters are strings (numbers in the file are written back in their shortest exact form). A render passes
// every parameter that applies to it to the scene as -D name=value (study-wide `parameters`, the surface's, the
// lamp's, the model's, `render.parameters`, `view`, `width`, `height`; later ones win); a BRDF job reads the
// study-wide, surface and model parameters as model options (bsdf/model_options.hpp names, e.g. model, sigma,
// corr_length, gamma, material, alpha_from, smoothing, cutoff_wavelengths).
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace surfscatter::study {

using Parameters = std::map<std::string, std::string>;

// One entry of `models`, `surfaces` or `lamps`.
struct Variant {
    std::string name;    // file names and job ids; letters, digits, '_', '-', '.'; empty for the implicit single one
    std::string label;   // caption on sheets and plots (default: the name)
    Parameters parameters;
    std::string origin;  // "study.json: models[2]", for messages
};

struct Crop {
    std::array<double, 3> focus{};  // world point, scene units (metres in scenes/photo-setup)
    double radius = 0;              // half-size of the square about it in its z plane
};

struct RenderSettings {
    int spp = 16;
    int width = 0, height = 0;           // film size passed as the scene parameters width, height (0: the scene's)
    std::optional<std::uint64_t> seed;   // default: the scene's sampler seed
    Parameters parameters;               // scene-only parameters for every render
    std::optional<Crop> crop;            // render only the pixels around `focus` (Mitsuba's crop window)
    bool overview = false;               // a low-resolution whole view with the crop outlined, on every sheet
    int columns = 0;                     // sheet columns; 0: from the panel count (sheet_caption.hpp)
};

struct AngleSettings {
    std::vector<double> theta_i;  // incidence angles, degrees
    double phi_i = 0;             // incidence azimuth, degrees
};

struct Study {
    std::string origin;             // the study file as the user named it (or the preset's name), for messages
    std::filesystem::path base;     // relative paths in the study (scene, surface_file) start here
    std::filesystem::path folder;   // outputs and manifest.json
    std::string scene;              // as written; resolved against `base`
    std::vector<std::string> views; // values of the scene parameter `view`
    Parameters parameters;          // every job
    std::vector<Variant> models, surfaces, lamps;  // surfaces and lamps: one implicit unnamed entry if not given
    std::vector<double> wavelengths;               // nm, BRDF slices and albedo tables
    std::optional<RenderSettings> render;
    std::optional<AngleSettings> slices, albedo;

    std::filesystem::path resolve(const std::string& path) const;  // absolute, against `base` if relative
    // The file parameters (surface_file: a height map) resolved, so that the scene and the BRDF jobs see the same.
    Parameters with_absolute_files(Parameters values) const;
};

// Reads and checks a study file: every key known, every name unique and usable in file names, every number in
// range; the error names the file and the entry ("study.json: models[2].name: ..."). The folder is the file's.
Study read_study(const std::filesystem::path& file);

// The same from JSON text; `origin` names it in messages.
Study parse_study(const std::string& json, const std::filesystem::path& base, const std::string& origin);

// The study as JSON text in the file format (what read_study reads back, with absolute paths).
std::string to_json(const Study& study);

}  // namespace surfscatter::study
