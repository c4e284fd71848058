#pragma once
// A fit's results as the front ends hand them out (docs/FIT.md): the JSON document (CLI OUT.json, Python's returned
// dict), the CSV of the data beside every model's fit and residual (OUT.csv, the plot's input) and the one-line
// summary per model.
#include <string>

#include <nlohmann/json.hpp>

#include "surfscatter/inverse/brdf_data.hpp"
#include "surfscatter/inverse/fit_brdf.hpp"

namespace surfscatter::inverse {

nlohmann::json fit_json(const BrdfData& data, const FitOptions& options, const FitResult& result);
// Columns: the data's (brdf_stderr if given), then <model>_fit and <model>_residual per model.
std::string fit_csv(const BrdfData& data, const FitResult& result);
// "ghs: sigma_um 0.1204 +- 0.0011, corr_length_um 2.03 +- 0.05, gamma unconstrained (...); relative rms 0.031"
std::string summary_line(const ModelFit& fit);

}  // namespace surfscatter::inverse
