#pragma once
// Statistics of a profile (a line scan, heightmap/line_scan.hpp): its rms height and slope along the line, its 1-D
// PSD, and the KC fitted to that PSD with the KC's profile PSD (KCorrelation::profile_psd_unit). A profile holds
// heights along one direction only; the fitted sigma_h, L_c and gamma describe an areal surface only under the
// assumption that the surface is isotropic (its PSD the same along every direction), which every output that uses
// them states (kIsotropyNote). docs/HEIGHTMAPS.md "Profiles".
//
// The 1-D PSD: P1(zeta_x) = integral of P(zeta_x, zeta_y) d zeta_y, so that the integral of P1 over the zeta_x-line
// is the variance. Estimated as the Hann-windowed periodogram dx / (2 pi sum w^2) |sum h w e^{-i zeta x}|^2 of the
// form-removed profile at zeta_k = 2 pi k / (N dx), averaged over bands of kProfileBandBins frequencies (each band
// one "ring" of a RadialPsd whose count makes effective_samples() the band's independent samples, about 2), so that
// fit_kc's weights and log-bias correction apply as they do to a map's rings.
#include <cstddef>
#include <string>

#include "surfscatter/heightmap/line_scan.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

inline constexpr std::size_t kProfileBandBins = 8;

// The note every output that treats a profile as a surface prints.
inline constexpr const char* kIsotropyNote =
    "a profile holds heights along one line: the surface is assumed isotropic (its PSD the same along every "
    "direction), so the KC fitted to the profile's 1-D PSD stands for the areal surface";

// What `surface fit` reports about a profile.
struct ProfileFit {
    KcFit kc;                     // fitted with options.profile = true
    RadialPsd psd;                // the 1-D PSD in bands (what was fitted)
    double rms_height_um = 0.0;   // of the form-removed profile
    double rms_slope = 0.0;       // central differences along the line
    double length_um = 0.0;       // first point to last
    double nyquist = 0.0;         // pi / dx
    // The fitted KC's profile PSD summed over the periodogram's frequencies against the periodogram's sum: the
    // variance the fit says the profile holds against what it holds.
    double fit_band_rms_um = 0.0, profile_band_rms_um = 0.0;
};

// The form-removed heights (invalid points 0) and their rms and rms slope. Form: none (the mean) or plane (a
// least-squares line); any other is an Error naming the profile.
struct ProfileMoments {
    std::vector<double> heights_um;
    double rms_height_um = 0.0, rms_slope = 0.0;
};
ProfileMoments profile_moments(const heightmap::LineScan& scan, heightmap::Form form);

// The 1-D PSD in bands (see above). Error naming the profile if a point is invalid (the masked estimator is areal
// only) or the profile is shorter than 16 points.
RadialPsd estimate_profile_psd(const heightmap::LineScan& scan, heightmap::Form form);

// Moments, PSD and the KC fit (options.form none or plane; options.profile is set here). The fit's failure, if
// any, is in kc.failure as for a map (require_resolved()).
ProfileFit fit_profile(const heightmap::LineScan& scan, KcFitOptions options = {});

}  // namespace surfscatter::surface
