#pragma once
// Which model to trust for a surface (docs/VALIDITY.md): the 1-D forms of GHS, SSA and Kirchhoff
// (bsdf/profile_lobes.hpp) against the rigorous exact-1d solution averaged over random profiles
// (reference/exact_1d_statistics.hpp), per wavelength, incidence and polarisation.
//
// The comparison is of the incoherent (diffuse) parts, per radian of scattering angle, over the directions where the
// reference is at least `peak_fraction` of its peak; directions whose Monte Carlo standard error exceeds
// `max_reference_stderr` of the reference value are left out (and counted), since there the reference cannot tell
// the models apart. The relative error at a direction is |model - reference| / reference; a row gives its median and
// worst over the directions used. Energies are coherent + the trapezoidal integral of the incoherent part over the
// 0.1 deg grid (the reference's coherent part is the Monte Carlo |<a>|^2 spread over the beam's angular width).
//
// Before comparing, the curves are averaged over theta_o bins (Criteria::bin_deg, bin_curves below).
// Verdict per (wavelength, incidence, polarisation): the model of smallest median error is trusted when that median
// is within `tolerance` plus the reference's own median relative standard error over the directions used (the
// reference's noise enters the measured error); no model is certified when that standard error exceeds the tolerance
// itself or no direction is usable. Even then a model whose median error exceeds the tolerance plus twice the
// reference's standard error is ruled out.
#include <cstddef>
#include <string>
#include <vector>

#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::validity {

struct Criteria {
    double peak_fraction = 0.01;        // directions used: reference >= this of its peak
    double max_reference_stderr = 0.25; // ... and its standard error <= this of its value
    double tolerance = 0.10;            // a model is trusted when its median relative error is within this
    double bin_deg = 3.0;               // theta_o bins the curves are averaged over before comparing; 0: none
};

// Throws Error naming the front end's spelling of the bad value unless tolerance is in (0, 1), bin_deg in [0, 30] and
// max_reference_stderr in (0, 1]; profile_validity and map_validity check them too (under the Python names).
void require_valid_criteria(const Criteria& criteria, const char* tolerance_name, const char* bin_name,
                            const char* stderr_name);

// Curves averaged over theta_o bins of `bin_rad` from -90 deg (the last bin takes the remainder): the speckle of
// a finite number of random profiles is averaged out over the bin. `theta_o_rad` becomes the bins' mean angles.
struct BinnedCurves {
    std::vector<double> theta_o_rad, reference, reference_stderr;
    std::vector<std::vector<double>> models;
};
// The standard error of a bin's mean is the root mean square of its directions' standard errors over
// sqrt(max(1, bin width / speckle width)): the speckle of one realization is correlated over the beam's angular
// spread, speckle width 2 / (k g cos theta_o) (beam width g, k = 2 pi / lambda), and independent beyond it. An
// estimate, not an exact variance: the per-realization far fields are not kept.
BinnedCurves bin_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                        const std::vector<double>& reference_stderr, const std::vector<std::vector<double>>& models,
                        double bin_rad, double k_per_um, double beam_width_um);

struct CurveComparison {
    double median_rel_error = 0;
    double worst_rel_error = 0;
    double worst_theta_o_rad = 0;
    std::size_t directions_used = 0;
    std::size_t directions_excluded = 0;       // above peak_fraction but with too large a standard error
    double reference_median_rel_stderr = 0;    // over the directions used
    std::vector<std::size_t> used;             // indices of the directions used
};

// `reference`, `reference_stderr` and `model` on the same grid `theta_o_rad`; throws Error on mismatched sizes.
CurveComparison compare_curves(const std::vector<double>& theta_o_rad, const std::vector<double>& reference,
                               const std::vector<double>& reference_stderr, const std::vector<double>& model,
                               const Criteria& criteria);

struct ModelResult {
    std::string model;  // ghs | ghs_ssa | kirchhoff
    CurveComparison comparison;
    double model_energy = 0;  // coherent + integral of the incoherent part
    std::vector<double> incoherent_per_rad;  // on the reference's grid, before binning
    double coherent = 0;
};

struct Verdict {
    bool conclusive = false;
    bool trusted = false;         // the best model is within the tolerance
    std::string best_model;       // empty when not conclusive
    std::vector<std::string> within_tolerance;
    std::vector<std::string> ruled_out;  // median error > tolerance + 2 x the reference's standard error
    std::string text;             // one plain sentence
};

Verdict decide(const std::vector<ModelResult>& models, const Criteria& criteria);

struct ProfileCase {
    double wavelength_nm = 0, theta_i_deg = 0;
    bsdf::ProfilePolarisation polarisation = bsdf::ProfilePolarisation::s;
    reference::StatisticalResult reference;
    double reference_energy = 0;
    BinnedCurves binned;  // what the comparison used; binned.models in the order of `models`
    std::vector<ModelResult> models;
    Verdict verdict;
};

struct ProfileStudy {
    std::vector<double> wavelengths_nm, theta_i_deg;
    std::vector<bsdf::ProfilePolarisation> polarisations;
    double beam_width_um = 0;
    double points_per_wavelength = 10;
    reference::StatisticalOptions statistical;  // length, realizations, seed, threads (progress: per case)
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
