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
// measured route for profiles"): the isotropic 2-D PSD whose line scans have the profile's 1-D PSD, by the inverse
// Abel transform of P1(zeta_x) = 2 int_{zeta_x}^inf P(z) z / sqrt(z^2 - zeta_x^2) dz,
//     P(z) = -(1 / pi) int_z^inf P1'(u) / sqrt(u^2 - z^2) du = -(1 / pi) int_0^inf P1'(z cosh t) dt.
// 1. The periodogram (profile_periodogram) is scaled to the profile's variance (window correction, as a map's) and
//    averaged over bands of kProfileBandBins bins that widen to kProfileBandWidth of their frequency, so that the
//    high frequencies, where a profile has many bins, rest on many samples: the derivative the transform takes
//    then follows the spectrum, not the periodogram's scatter (each bin's standard error is 100 %).
// 2. ln P1 between band centres is a cubic Hermite polynomial in ln zeta through the centres with slopes from the
//    neighbouring secants (P1' continuous, so P has no cusps; exact for power laws); below the first band's centre
//    u0, P1 continues as the even parabola P1(0) - b u^2 through the first two bands (b >= 0: not rising towards
//    zero; the 1-D PSD of a surface with a finite correlation range is smooth and even at zero; measured on KC, a
//    flat continuation read P 9 % low at the first bins); beyond the last band it continues as the power law fitted to the last octave's
//    bands (a spectrum rising there is continued flat), only so that P near Nyquist has the integral's tail: the
//    models use P up to Nyquist and roll it off beyond, as a map's.
// 3. P is evaluated at z = k dzeta, k = 0 .. n/2 (the profile's own bins, Gauss-Legendre in t on each power-law
//    segment: the quadrature error is far below the spectrum's scatter) and read as a map's ring means are
//    (ring_psd.hpp). Where the transform of a noisy spectrum comes out <= 0 (P1 locally rising), the node is skipped
//    and counted (clipped_nodes()).
// 4. sigma_h^2, the integral of P, is scaled to the profile's variance (band_scale()), as a map's is to the map's:
//    the factor corrects what skipped nodes and the continuations add or leave out (measured 0.93-1.0 on rows of a
//    synthesised map; without it sigma came out 7 % high on average, the skipped nodes' interpolation).
inline constexpr double kProfileBandWidth = 0.1;

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

    // The banded 1-D PSD the transform read (window-corrected, um^3) and the tail's power beyond it (P1 ~ zeta^-a).
    const std::vector<double>& band_zeta() const { return band_zeta_; }
    const std::vector<double>& band_psd() const { return band_psd_; }
    double tail_power() const { return tail_power_; }
    std::size_t clipped_nodes() const { return clipped_; }
    std::size_t nodes() const { return nodes_; }
    // The factor on the transform that makes sigma_h the profile's rms (step 4 above).
    double band_scale() const { return band_scale_; }
    // P(z) (um^4) by the inverse Abel transform of the banded P1 (before clipping): what the nodes hold.
    double abel_inverse(double z) const;

private:
    double dzeta_ = 0, nyquist_ = 0, rms_um_ = 0, window_scale_ = 1, tail_power_ = 0, parabola_ = 0, band_scale_ = 1;
    std::size_t clipped_ = 0, nodes_ = 0;
    std::vector<double> band_zeta_, band_psd_, band_slope_;  // band_slope_: d ln P1 / d ln zeta at each centre
    std::vector<double> bin_variance_;  // dzeta x multiplicity x P1 of each non-DC bin (the standard error's)
    std::shared_ptr<const RadialStatistics> psd_;
};

// The note every model on a profile's measured spectrum prints: the isotropy assumed and what was extrapolated.
std::string measured_profile_note(const ProfileStatistics& s, const std::string& origin);

}  // namespace surfscatter::surface
