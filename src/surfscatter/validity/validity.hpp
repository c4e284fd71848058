#pragma once
// Which model to trust for a surface (docs/VALIDITY.md): the 1-D forms of GHS, SSA, Kirchhoff, GGX from statistics
// and two_scale (bsdf/profile_lobes.hpp) against the rigorous exact-1d solution averaged over random profiles
// (reference/exact_1d_statistics.hpp), per wavelength, incidence and polarisation.
//
// The comparison is of the incoherent (diffuse) parts, per radian of scattering angle, over the directions where the
// reference is at least `peak_fraction` of its peak; directions whose Monte Carlo standard error exceeds
// `max_reference_stderr` of the reference value are left out (and counted), since there the reference cannot tell
// the models apart. The relative error at a direction is |model - reference| / reference; a row gives its median and
// worst over the directions used. Energies are coherent + the trapezoidal integral of the incoherent part over the
// 0.1 deg grid (the reference's coherent part is the Monte Carlo |<a>|^2 spread over the beam's angular width).
//
// Before comparing, the profile route averages each model over the reference beam's incident plane waves
// (beam_blurred below) and the curves are averaged over theta_o bins (Criteria::bin_deg, bin_curves below).
// Verdict per (wavelength, incidence, polarisation), validity::decide (docs/VALIDITY.md "Verdicts"):
// * the reference is outside its own validity (no direction usable, its median relative standard error above the
//   tolerance, or a reason the route gives, e.g. map sub-areas too small to resolve the lobe): nothing is concluded
//   and no model is ruled out;
// * otherwise a model's error e (median relative error) has the uncertainty u: the median over the directions used
//   of the largest change of |m_j / r_j - 1| when the reference moves by +-eps_j of its value (eps_j its relative
//   standard error), combined in quadrature with the model's own stated accuracy. The lead of the best model a
//   over another b has the uncertainty u_ab: the median of the largest change of |m_b / r - 1| - |m_a / r - 1| for
//   the same moves (the reference's error is common to both: it cancels where both lie on the same side of the
//   reference beyond its error, adds where they straddle it, and counts in full where a move would carry it past
//   one of them), combined with both models' own accuracies in quadrature;
// * a is trusted when e_a <= tolerance and e_b - e_a > max(u_ab, kUsefulLead x tolerance) for every other model b:
//   a lead must be beyond the uncertainty and also worth acting on (docs/VALIDITY.md "Verdicts": below a tenth of
//   the tolerance, a user who accepts errors up to the tolerance has no reason to prefer one model); the models b
//   with e_b - e_a <= max(u_ab, kUsefulLead x tolerance) are indistinguishable from a and the verdict names them; a
//   model with e > tolerance + 2 u is ruled out.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::validity {

// The smallest lead, as a fraction of the tolerance, that makes a model trusted over another (header, decide).
inline constexpr double kUsefulLead = 0.1;

struct Criteria {
    double peak_fraction = 0.01;        // directions used: reference >= this of its peak
    double max_reference_stderr = 0.25; // ... and its standard error <= this of its value
    double tolerance = 0.10;            // a model is trusted when its median relative error is within this
    double bin_deg = 3.0;               // theta_o bins the curves are averaged over before comparing; 0: none
};

// Throws Error naming the front end's spelling of the bad value (names.tolerance, bin_deg, max_reference_stderr:
// the CLI's options, Python's keywords) unless tolerance is in (0, 1), bin_deg in [0, 30] and max_reference_stderr in
// (0, 1]; profile_validity and map_validity check them with their study's option_names.
void require_valid_criteria(const Criteria& criteria, const reference::OptionNames& names);

// Curves averaged over theta_o bins of `bin_rad` from -90 deg (the last bin takes the remainder): the speckle of
// a finite number of random profiles is averaged out over the bin. `theta_o_rad` becomes the bins' mean angles.
struct BinnedCurves {
    std::vector<double> theta_o_rad, reference, reference_stderr;
    std::vector<std::vector<double>> models;
    std::vector<std::size_t> first_direction;  // per bin, the index of its first direction on the input grid
    std::vector<char> near_specular;     // 1 for a bin mark_near_specular leaves out of the comparison (or empty)
    std::size_t near_specular_bins = 0;
};
// The standard error of a bin's mean is the root mean square of its directions' standard errors over
// sqrt(max(1, bin width / speckle width)): the speckle of one realization is correlated over the beam's angular
// spread, speckle width 2 / (k g cos theta_o) (beam width g, k = 2 pi / lambda), and independent beyond it. An
// estimate, not an exact variance: the per-realization far fields are not kept.
BinnedCurves bin_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                        const std::vector<double>& reference_stderr, const std::vector<std::vector<double>>& models,
                        double bin_rad, double k_per_um, double beam_width_um);

// How far from specular (rad, either side) the reference's incoherent part cannot be told from its coherent part:
// its beam spreads the specular reflection over the Thorsos beam's angular spectrum, whose intensity falls to e^-2
// at the reference's beam_half_width_rad (2 / (k g cos theta_i)); twice that (intensity e^-8).
double near_specular_half_width_rad(const reference::StatisticalResult& reference);
// Marks the bins of `bin_rad` any part of which lies within `half_width_rad` of theta_i (near_specular, counted in
// near_specular_bins): compare_curves leaves them out, so that a verdict never rests on them.
void mark_near_specular(BinnedCurves& binned, double theta_i_rad, double half_width_rad, double bin_rad);

// The reference beam's kernel (docs/VALIDITY.md "The beam's kernel"): exact-1d's statistical mean is the plane-wave
// ensemble's lobe averaged over the beam's incident plane waves, in the incident horizontal wavenumber
// K = k sin theta with the weight cos theta(K) exp(-(K - k sin theta_i)^2 g^2 / 2) (Thorsos' beam's |A(K)|^2, a
// Gaussian of standard deviation 1/g in K, times the power each plane wave carries down; docs/REFERENCE.md). A
// plane-wave model is averaged the same way before it is compared, so that like is compared with like.
// `lobe(theta, theta_o)`: the model's incoherent part per radian at incidence theta in [0, 90) deg on the directions
// theta_o (a negative incidence is read from the mirrored directions, the profiles' statistics being symmetric).
using LobeAtIncidence = std::function<std::vector<double>(double theta_i_rad, const std::vector<double>& theta_o_rad)>;
// Gauss-Hermite in K with 3, 5, 9 or 17 nodes, the fewest whose error, estimated on the lobe's fast dependence (the
// nominal curve shifted by K - k sin theta_i in k sin theta_o, against a 97-point trapezoid of the same shifts),
// is <= kBlurRuleTolerance: the median over the directions where the nominal curve is >= 1 % of its peak outside
// twice the beam's 1/e^2 half-width 2 / (k g cos theta_i) of specular (where validity compares). Lobes that change
// within 1/g in K (correlation lengths above about g / 2) may need 17 and keep a larger error, stated.
inline constexpr double kBlurRuleTolerance = 1e-3;
struct BlurredLobe {
    std::vector<double> intensity_per_rad;  // on theta_o_rad
    int nodes = 0;                          // Gauss-Hermite nodes used (the model evaluated at nodes - 1 more incidences)
    double rule_error = 0;                  // the estimate above, relative
};
// `nominal` = lobe(theta_i_rad, theta_o_rad); theta_o_rad strictly increasing within [-pi/2, pi/2]. `needed` (empty:
// all): the directions where the average is wanted (the others keep the nominal value, and the lobe is evaluated
// at the other incidences only there; the rule's error is estimated there). Throws Error for mismatched sizes, a
// grid out of order, theta_i outside [0, 90) deg or a beam width or k not > 0.
BlurredLobe beam_blurred(const LobeAtIncidence& lobe, const std::vector<double>& nominal,
                         const std::vector<double>& theta_o_rad, double k_per_um, double theta_i_rad,
                         double beam_width_um, const std::vector<char>& needed = {});

struct CurveComparison {
    double median_rel_error = 0;
    double worst_rel_error = 0;
    double worst_theta_o_rad = 0;
    std::size_t directions_used = 0;
    std::size_t directions_excluded = 0;       // above peak_fraction but with too large a standard error
    double reference_median_rel_stderr = 0;    // over the directions used
    std::vector<std::size_t> used;             // indices of the directions used
    // At the directions used: model / reference - 1, and the reference's standard error / its value.
    std::vector<double> rel_deviation, reference_rel_stderr;
};

// `reference`, `reference_stderr` and `model` on the same grid `theta_o_rad`; the directions flagged in `left_out`
// (empty: none) are not used but count for the reference's peak. Throws Error on mismatched sizes.
CurveComparison compare_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                               const std::vector<double>& reference_stderr, const std::vector<double>& model,
                               const Criteria& criteria, const std::vector<char>& left_out = {});

struct ModelResult {
    std::string model;  // ghs | ghs_ssa | kirchhoff | ggx_stats | two_scale (map route: the factory's names)
    CurveComparison comparison;
    double model_energy = 0;  // coherent + integral of the incoherent part
    // On the reference's grid, before binning: the profile route's as compared, averaged over the reference beam's
    // incident plane waves (beam_blurred); model_energy and coherent are the plane-wave model's.
    std::vector<double> incoherent_per_rad;
    double coherent = 0;
    double own_rel_uncertainty = 0;  // the model's stated numerical accuracy, relative (with beam_blurred's rule_error)
    int blur_nodes = 0;              // beam_blurred's nodes (0: not blurred, the map route)
};

// Uncertainty of a model's median error from the reference's noise and its own accuracy (header).
double error_uncertainty(const ModelResult& model);
// Uncertainty of the difference of two models' median errors against the same reference (header).
double lead_uncertainty(const ModelResult& a, const ModelResult& b);

struct Verdict {
    bool conclusive = false;      // the reference is within its validity: the comparison stands
    bool trusted = false;         // best_model is within the tolerance and ahead of every other beyond uncertainty
    std::string best_model;       // the smallest median error; empty when not conclusive
    std::vector<std::string> indistinguishable;  // with best_model, those whose lead is within the uncertainty
    std::vector<std::string> within_tolerance;
    std::vector<std::string> ruled_out;  // median error > tolerance + 2 x its uncertainty; none when not conclusive
    std::string reference_problem;  // why the reference is outside its validity; empty when it is within
    std::string text;               // one plain sentence
};

// `reference_problem`: why the route's reference is outside its validity here (empty when it is not known to be);
// `names`: the caller's options, for the remedy when the reference's standard error is too large (more realizations,
// where the route takes them - an empty names.realizations says it does not - or wider bins).
Verdict decide(const std::vector<ModelResult>& models, const Criteria& criteria,
               const std::string& reference_problem = {}, const reference::OptionNames& names = {});

struct ProfileCase {
    double wavelength_nm = 0, theta_i_deg = 0;
    bsdf::ProfilePolarisation polarisation = bsdf::ProfilePolarisation::s;
    reference::StatisticalResult reference;
    double reference_energy = 0;
    BinnedCurves binned;  // what the comparison used; binned.models in the order of `models`
    // ghs, ghs_ssa, kirchhoff, then ggx_stats where its rms slope is finite and two_scale (else in not_compared)
    std::vector<ModelResult> models;
    std::vector<std::string> not_compared;  // why a model is left out
    Verdict verdict;
    Verdict render_verdict;  // among the models a renderer offers (all but kirchhoff)
    // The reference's median relative standard error over the bins the comparison uses (infinite when none is
    // usable), and whether it reached the target standard error within the cap on realizations (true without one).
    double reference_rel_stderr = 0;
    bool target_reached = true;
    // The estimate of the reference's error from the profile's ends: the median over the bins used of what a flat
    // profile of the same length diffracts (its pattern against one twice as long) over the reference's incoherent
    // part. Above the tolerance, the reference is outside its validity.
    double edge_rel_error = 0;
};

struct ProfileStudy {
    std::vector<double> wavelengths_nm, theta_i_deg;
    std::vector<bsdf::ProfilePolarisation> polarisations;
    double beam_width_um = 0;
    double points_per_wavelength = 10;
    reference::OptionNames option_names;  // as the caller spells them (criteria, exact-1d's bounds and remedies)
    // length, realizations (a fixed count; with a target, the cap), seed, threads (progress: per case)
    reference::StatisticalOptions statistical;
    // > 0: realizations run until the reference's median relative standard error over the bins used reaches it
    // (statistical.realizations the most), in rounds, the first of statistical.first_round; 0: a fixed count.
    double target_rel_stderr = 0;
    Criteria criteria;
    bool progress = false;  // one bar over all cases x realizations, with ETA
};

// Every (wavelength, incidence, polarisation), in that nesting order. Stops between cases, or inside one, when
// interrupt_requested(): the cases completed are returned (a case cut short is dropped). Throws Error for bad input.
std::vector<ProfileCase> profile_validity(const surface::RadialStatistics& statistics,
                                          const material::Conductor& conductor, const ProfileStudy& study);

std::string to_string(bsdf::ProfilePolarisation polarisation);

// One row per model and case, as `surfscatter validity` writes OUT.csv and Python returns its table.
struct TableRow {
    std::string model;
    double wavelength_nm = 0, theta_i_deg = 0;
    std::string polarisation;
    CurveComparison comparison;
    double model_energy = 0, reference_energy = 0;
    bool trusted = false;  // this model is the case's verdict
    std::string verdict;
    double phi_i_deg = 0;         // the map route's incidence azimuth (0 for profiles)
    bool reference_valid = true;  // the map route: the Kirchhoff reference is within its validity
};
std::vector<TableRow> table(const std::vector<ProfileCase>& cases);

}  // namespace surfscatter::validity
