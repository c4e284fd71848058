#pragma once
// A study's independent jobs. Order = the order in which they are handed out (a job depends only on earlier ones):
//   tables/<surface>/<model>         loads the first render's scene of the (surface, model) pair (or builds its
//                                    BSDF if it has no render), which builds its lobe tables into the disk cache;
//                                    the pair's other jobs wait for it, so the tables are built once per study
//   render/<surface>/<lamp>/view<v>/<model>   renders/<surface>/<lamp>/view<v>/<model>.exr + .png
//   overview/<surface>/<lamp>/view<v>         renders/.../view<v>/overview.png (the whole view, crop outlined)
//   slice/<surface>/<wl>nm/<model>            brdf/<surface>/slice_<wl>nm_<model>.csv (in-plane BRDF)
//   albedo/<surface>/<wl>nm/<model>           brdf/<surface>/albedo_<wl>nm_<model>.csv (directional albedo)
//   sheet/<surface>/<lamp>/view<v>            sheets/<surface>_<lamp>_view<v>.png (compare-models' layout)
//   slice-plot/<surface>/<wl>nm, albedo-plot/<surface>/<wl>nm   the models of one surface and wavelength together
//                                                               (brdf/<surface>/{slice,albedo}_<wl>nm.csv + .png)
// Levels for the implicit single surface or lamp are left out of ids and paths.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "surfscatter/study/study.hpp"

namespace surfscatter::study {

enum class JobKind { tables, render, overview, slice, albedo, sheet, slice_plot, albedo_plot };
const char* to_string(JobKind kind);

struct Job {
    std::string id;
    JobKind kind{};
    // Everything the job's outputs depend on; what it reads to run (the manifest compares it on resume).
    nlohmann::json parameters;
    std::vector<std::string> outputs;  // relative to the study folder
    std::vector<std::string> inputs;   // outputs of other jobs that it reads (sheets and plots)
    std::vector<int> dependencies;     // indices of earlier jobs
};

std::vector<Job> expand(const Study& study);

}  // namespace surfscatter::study
