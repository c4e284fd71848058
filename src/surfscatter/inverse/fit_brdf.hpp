#pragma once
// Fits each scattering model's surface statistics to a measured BRDF (docs/FIT.md): non-linear least squares
// (Eigen's Levenberg-Marquardt, forward differences: the models are built from tables, not templated code) in
// ln sigma, ln L, ln(gamma - 1) (and ln LV, lay angle), inside bounds, from the best of several starts; standard errors and
// correlations from the Jacobian at the optimum, (J^T W J)^-1, scaled by chi2/dof when the data carry no errors;
// parameters the data do not constrain are reported as such, never given a number.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/inverse/brdf_data.hpp"

namespace surfscatter::inverse {

// The fitted parameters, by the names the CLI (--fix NAME=VALUE), JSON, CSV and Python use.
inline constexpr const char* kParameterNames[] = {"sigma_um", "corr_length_um", "gamma", "corr_length_v_um",
                                                  "lay_angle_deg"};

// How messages name the fit's options: the CLI's, unless a front end passes its own (Python's keywords), as every
// library check that names a caller's argument takes the name from the caller (docs/RELIABILITY.md).
struct FitOptionNames {
    std::string fix = "--fix", psd = "--psd", anisotropic = "--anisotropic", profile = "--profile";
};

struct FitOptions {
    std::vector<bsdf::ModelKind> models = {bsdf::ModelKind::ghs, bsdf::ModelKind::ghs_ssa, bsdf::ModelKind::ggx,
                                           bsdf::ModelKind::two_scale};
    std::string material = "perfect";  // as bsdf::ModelOptions::material: a metal, a file, or "perfect"
    bsdf::PsdKind psd = bsdf::PsdKind::kc;  // kc or gaussian (gaussian has no gamma)
    bool anisotropic = false;               // also corr_length_v_um and lay_angle_deg
    std::map<std::string, double> fixed;    // parameters held at a value (kParameterNames)
    // 1-D data of this polarisation (docs/FIT.md "Profiles"): the rows lie in the plane of incidence (phi_i 0, phi_o 0
    // or 180), `brdf` holds the scattered power per radian over the incident power of a profile z = h(x), as
    // `reference exact-1d`'s statistical mode gives it, and the models are the 1-D forms of bsdf/profile_lobes.hpp
    // (ghs, ghs_ssa, ggx_stats; two_scale has none); not with `anisotropic`.
    std::optional<bsdf::ProfilePolarisation> profile;
    int starts = 3;                          // sigma starts at g0 = 3, 0.5, 15 (the first `starts` of them)
    int refined = 1;                         // the solver runs from the `refined` starts of smallest misfit
    int max_evaluations_per_start = 30;      // model evaluations of the residuals per start (Jacobians apart)
    FitOptionNames names;
};

struct ParameterEstimate {
    std::string name;
    double value = 0;
    bool fixed = false;
    bool constrained = true;              // false: the data do not determine it (see `note`)
    std::optional<double> standard_error;  // none when fixed or unconstrained
    std::string note;                     // why it is unconstrained ("at the lower bound 1.02", ...)
};

struct ModelFit {
    bsdf::ModelKind model = bsdf::ModelKind::ghs;
    std::vector<ParameterEstimate> parameters;               // every parameter of the fit, fixed ones too
    std::vector<std::string> free;                           // names of the fitted parameters, in `correlation`'s order
    std::vector<std::vector<std::optional<double>>> correlation;  // among the constrained free parameters
    std::vector<std::string> degenerate_directions;  // parameter combinations the data do not constrain
    bool with_errors = false;       // the data carried brdf_stderr: misfit is chi2 / dof, else the relative rms
    double misfit = 0;              // chi2 / dof, or sqrt(mean ((model - data) / data)^2)
    double sum_squares = 0;         // sum of the squared (weighted) residuals
    std::size_t dof = 0;            // rows minus free parameters
    std::vector<double> fitted;     // the model at each row (1/sr)
    std::vector<double> residual;   // (model - data) / stderr, or (model - data) / data
    std::vector<std::size_t> worst; // the rows that misfit most, worst first (at most 5)
    int evaluations = 0;            // models built
    double cpu_seconds = 0;
    std::vector<std::string> notes; // what the user should know (bounds imposed by the model, ...)
};

struct FitResult {
    std::vector<ModelFit> fits;
    std::size_t best = 0;                       // index into fits of the smallest misfit
    std::vector<std::size_t> indistinguishable; // other fits whose misfit is within the statistical spread of best's
    std::string verdict;                        // one line saying which fits best, and which cannot be told apart
};

// Throws Error for bad options (a fixed name that is not a parameter or does not apply, a bad value) or data
// (validate()), or when the data hold no more rows than free parameters.
FitResult fit_brdf(const BrdfData& data, const FitOptions& options);

}  // namespace surfscatter::inverse
