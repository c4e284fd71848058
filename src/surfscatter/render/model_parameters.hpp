#pragma once
// The options of surfscatter's BSDF plugins (ghs, ghs_ssa, ggx_stats, two_scale; bsdfs/scattering_models.cpp),
// read once for scenes and for front ends that have parameters as text but no scene (a study's BRDF slices and
// albedo tables), so that both mean the same by the same names (defaults included: ggx_stats takes alpha_from =
// measured).
#include <map>
#include <string>
#include <vector>

#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/render/properties.hpp"

namespace surfscatter::render {

// From a plugin element's Properties; `type` is the plugin type. Errors name the element ("file:line: bsdf ...").
bsdf::ModelOptions scattering_model_options(Properties& props, const std::string& type);

// From name = value text, as a <bsdf type="`type`"> with one <float>/<string>/<boolean> per entry would give them;
// every name must be a parameter of the plugin (an unknown one is an error). Messages start with `origin`; notes
// for the user (a height map read) go to `notes`.
bsdf::ModelOptions scattering_model_options(const std::string& type, const std::map<std::string, std::string>& parameters,
                                            const std::string& origin, std::vector<std::string>* notes = nullptr);

}  // namespace surfscatter::render
