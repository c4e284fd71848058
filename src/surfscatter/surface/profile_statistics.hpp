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
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/heightmap/line_scan.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/measured_statistics.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

inline constexpr std::size_t kProfileBandBins = 8;

// The note every output that treats a profile as a surface prints.
inline constexpr const char* kIsotropyNote =
    "a profile holds heights along one line: the surface is assumed isotropic (its PSD the same along every "
    "direction), so the KC fitted to the profile's 1-D PSD stands for the areal surface";

// The note every output that takes a profile's own spectrum as an areal surface's prints.
inline constexpr const char* kMeasuredIsotropyNote =
    "a profile holds heights along one line: the surface is assumed isotropic (its PSD the same along every "
    "direction), so the 2-D PSD whose line scans have the profile's 1-D PSD stands for the areal surface";

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

// The Hann-windowed periodogram of the form-removed profile at zeta_k = k dzeta, k = 0 .. n/2 (see above), as
// measured (no window correction): um^3, P1 per unit zeta_x on the two-sided line. Error naming the profile if a
// point is invalid or the profile is shorter than 16 points.
struct ProfilePeriodogram {
    double dzeta = 0.0;           // 2 pi / (n dx), rad/um
    std::vector<double> psd;      // k = 0 .. n/2
    std::size_t points = 0;       // n: bin n/2 of an even n is its own mirror
    double rms_um = 0.0;          // of the form-removed profile (what the window correction scales the sum to)
    std::string origin;
    // The variance the bins hold: dzeta (P_0 + 2 sum of the others), the Nyquist bin of an even n once.
    double sum() const;
};
ProfilePeriodogram profile_periodogram(const heightmap::LineScan& scan, heightmap::Form form);

// The 1-D PSD in bands (see above). Error naming the profile if a point is invalid (the masked estimator is areal
// only) or the profile is shorter than 16 points.
RadialPsd estimate_profile_psd(const heightmap::LineScan& scan, heightmap::Form form);

// Moments, PSD and the KC fit (options.form none or plane; options.profile is set here). The fit's failure, if
// any, is in kc.failure as for a map (require_resolved()).
ProfileFit fit_profile(const heightmap::LineScan& scan, KcFitOptions options = {});

// A profile's own spectrum as an isotropic surface's (`--psd measured` with a profile; docs/HEIGHTMAPS.md "The
// measured route for profiles"): the isotropic 2-D PSD P whose line scans have the profile's 1-D PSD, i.e. the
// inverse of the Abel transform P1(u) = 2 int_u^inf P(z) z / sqrt(z^2 - u^2) dz. The inverse differentiates P1, so
// applied to a measured spectrum (each periodogram bin has a standard error of 100 %) it comes out negative wherever
// the noise makes P1 rise locally; made positive there it gained variance that a scale on the whole spectrum then
// took from every frequency (ghs 0.71 x the truth's on a synthesised KC profile). Instead P is fitted:
// 1. The periodogram (profile_periodogram) is scaled to the profile's variance (window correction, as a map's) and
//    averaged over bands of kProfileBandBins bins that widen to kProfileBandWidth of their frequency.
// 2. ln P is piecewise linear in ln z at knots an octave apart at the lowest bins (1, 2, 4, ...), then
//    kProfileKnotBins bins apart, widening to kProfileKnotRatio (the last at Nyquist), constant below the first knot
//    and falling as z^-a beyond the last (a the last interval's power, at least kProfileMinTailPower): P > 0 by
//    construction, and the knots' spacing, not the bins', sets how finely the noisy spectrum is resolved.
// 3. The knots' ln P maximise the likelihood of the bands (Levenberg-Marquardt on the deviance residuals of a mean of
//    n exponential samples, 2 n (q - 1 - ln q), q = band / model), the model being the forward Abel transform of P
//    averaged over each band's bins (at most 8 of them; Gauss-Legendre in t, z = u cosh t, on each knot interval: no
//    singularity). The forward transform smooths, so the fit is stable where the inverse was not. A smoothness
//    prior, kProfileSmoothing^2 x the bending energy of ln P in ln z, ties the knots the data hardly constrain (the
//    lowest) to their neighbours.
// 4. P is evaluated at z = k dzeta, k = 0 .. n/2 (the profile's own bins) and read as a map's ring means are
//    (ring_psd.hpp), sigma_h^2, its integral, scaled to the profile's variance (band_scale(), as a map's): the fit's
//    variance is within a few % of the profile's, the scale corrects what the band beyond Nyquist holds.
// Accuracy (tests/surface/test_profile_statistics.cpp, docs/HEIGHTMAPS.md): on the KC's exact profile PSD, and on
// synthesised KC profiles, P and the ghs lobe against the KC's closed forms.
inline constexpr double kProfileBandWidth = 0.1;
inline constexpr std::size_t kProfileKnotBins = 16;
inline constexpr double kProfileKnotRatio = 1.25;
inline constexpr double kProfileMinTailPower = 2.0;
inline constexpr double kProfileSmoothing = 0.5;

class ProfileStatistics final : public MeasuredStatistics {
public:
    ProfileStatistics(const heightmap::LineScan& scan, heightmap::Form form);
    explicit ProfileStatistics(ProfilePeriodogram periodogram);

    double sigma_h() const override { return psd_->sigma_h(); }
    double psd_unit(double zeta) const override { return psd_->psd_unit(zeta); }
    double acv_normalized(double r) const override { return psd_->acv_normalized(r); }
    double radial_cdf(double zeta) const override { return psd_->radial_cdf(zeta); }
    double correlation_length() const override { return psd_->correlation_length(); }
    std::string cache_key() const override { return psd_->cache_key(); }

    double map_rms() const override { return rms_um_; }      // the profile's rms after form removal
    double first_ring() const override { return dzeta_; }
    double ring_width() const override { return dzeta_; }
    double nyquist() const override { return nyquist_; }
    double sigma_relative_error() const override;
    double window_scale() const override { return window_scale_; }

    // The banded 1-D PSD the fit read (window-corrected, um^3).
    const std::vector<double>& band_zeta() const { return band_zeta_; }
    const std::vector<double>& band_psd() const { return band_psd_; }
    std::size_t knots() const { return log_knots_.size(); }
    double tail_power() const;  // a of P ~ z^-a beyond the last knot
    // The fitted P(z) (um^4, before band_scale()) and its Abel transform, the profile PSD P1(u) it implies (um^3).
    double fitted_psd(double z) const;
    double fitted_profile_psd(double u) const;
    // The factor on the fit that makes sigma_h the profile's rms (step 4 above).
    double band_scale() const { return band_scale_; }

private:
    double dzeta_ = 0, nyquist_ = 0, rms_um_ = 0, window_scale_ = 1, band_scale_ = 1;
    std::vector<double> band_zeta_, band_psd_;
    std::vector<double> log_knots_, log_psd_;  // ln z and the fitted ln P at the knots
    std::vector<double> bin_variance_;  // dzeta x multiplicity x P1 of each non-DC bin (the standard error's)
    std::shared_ptr<const RadialStatistics> psd_;
};

// The note every model on a profile's measured spectrum prints: the isotropy assumed and what was extrapolated.
std::string measured_profile_note(const ProfileStatistics& s, const std::string& origin);

}  // namespace surfscatter::surface
