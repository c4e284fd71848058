#pragma once
// Loader for the YAML files of the refractiveindex.info database (Polyanskiy, Sci. Data 11, 94 (2024)), parsed with
// yaml-cpp. A file's DATA list holds one or two entries: `tabulated nk`, or `tabulated n` / `formula 1..9` for n
// together with an optional `tabulated k`. Wavelengths there are in micrometres; this API is in nm.
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::material {

// The database's dispersion formulas 1-9 ("Sellmeier", "Sellmeier-2", "Polynomial", "RefractiveIndex.INFO",
// "Cauchy", "Gases", "Herzberger", "Retro", "Exotic"), c = coefficients C1.. as listed in the file, lambda in um.
// Returns n (real). Throws Error for an unknown formula, too many coefficients, or a result that is not a real
// positive index (e.g. a pole of the formula).
double dispersion_formula_index(int formula, const std::vector<double>& c, double lambda_um);

// Throws Error naming the file (and the DATA entry or line) for anything the loader cannot use.
std::shared_ptr<const RefractiveIndex> load_refractiveindex_info_yaml(const std::string& path);
// Same from the file's text; `path` names it in messages.
std::shared_ptr<const RefractiveIndex> parse_refractiveindex_info_yaml(const std::string& text, const std::string& path);

}  // namespace surfscatter::material
