#pragma once
// A measured height map's own statistics for the scattering models (`--psd measured`): the map's 2-D spectrum
// averaged over rings, within the band the map resolves, with no model fitted and no power law extrapolated.
//
// Construction (docs/HEIGHTMAPS.md, "Measured statistics for the models"):
// 1. The form is removed (heightmap/form.hpp) and the 2-D periodogram taken (psd_estimate.hpp). A map that wraps
//    around seamlessly (its jumps across opposite edges are no larger than its steps between neighbours, as for
//    synthesised periodic maps: wrap_jump_ratio()) gets the rectangular window, under which its periodogram is
//    exact and neighbouring bins do not mix; any other map (instrument data) the Hann window, which keeps the
//    jump between unrelated edges from leaking into the tail (and smears +-2 bins); maps with invalid points the
//    masked correlogram.
// 2. Every ring of width dzeta (= 2 pi / shorter side) from the first to the Nyquist ring pi / coarser spacing is
//    its own sample (no merging): its mean P at its mean |zeta|. Between rings ln P is linear in zeta (exact for a
//    Gaussian PSD's exponential fall, second order elsewhere). Rings whose mean is not positive (masked estimates
//    far below their scatter) are skipped and counted.
// 3. The band: beyond Nyquist P falls as zeta^-200 from its value there (continuous, so that the lobe tables keep
//    their fast path; 0.02x at 1.02 zeta_N), so next to nothing beyond what the map holds is used, whatever the
//    tail does (an instrument's noise floor flatter than zeta^-2 included); that share is reported
//    (above_band_fraction()). Below the first ring (periods longer than the map) P runs linearly from P(0) to the
//    first ring, as a bilinear reading of the lattice does, P(0) being the DC bin continued from the lattice's
//    lowest ring (lowest_ring_mean(): the periodogram's own DC value is what removing the mean left, 0 with the
//    rectangular window, and put a hole in the lobe's core at specular); nothing is extrapolated beyond the lowest
//    ring. Its share of the variance is reported (below_band_fraction()).
// 1b. Window correction: the periodogram is scaled so that its total is the map's own variance (the Hann window's
//    total is the centre-weighted variance): window_scale().
// 4. sigma_h^2 is the integral of that P, which equals the periodogram's sum over the disc of the band (Parseval):
//    the ring means are scaled by the one factor that makes it so (band_scale(), within 1 % of 1: the lowest rings
//    hold more lattice points than their annuli's area), plus the small share rolled off; the map's own rms (all of its variance, corners of the lattice beyond the
//    Nyquist disc included) is reported beside it (map_rms()). The self-convolutions are exact transforms of the
//    resulting rho^m (eq. 2).
// Uncertainty: a ring mean over nu independent periodogram values (ring_samples(): effective_samples() of its
// lattice points) has relative standard error 1/sqrt(nu), large for the first rings of any map: lobes that draw on
// periods longer than a third of the map (zeta < 3 dzeta) rest on few samples, and the models say so.
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/surface/measured_statistics.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

class MapRingPsd;

class MapStatistics final : public MeasuredStatistics {
public:
    // Error if fewer than kMinFitValidFraction of the points are valid or the form leaves no roughness.
    MapStatistics(const heightmap::HeightMap& map, heightmap::Form form);

    double sigma_h() const override;
    double psd_unit(double zeta) const override;
    double acv_normalized(double r) const override;
    double radial_cdf(double zeta) const override;
    double correlation_length() const override;
    std::string cache_key() const override;

    // What the estimate rests on, for reports.
    bool periodic() const { return periodic_; }               // rectangular window (see above)
    double map_rms() const override { return map_rms_; }      // rms of the form-removed map over its valid points, um
    double first_ring() const override { return radial_.zeta.front(); }  // the lowest frequency the map resolves
    double ring_width() const override { return radial_.dzeta; }  // dzeta, rad/um
    double nyquist() const override { return nyquist_; }      // top of the band, rad/um
    std::size_t skipped_rings() const { return skipped_rings_; }
    // The factor on the ring means that makes the continuous PSD carry the lattice's sum over the band (Parseval).
    double band_scale() const { return band_scale_; }
    // The window correction on the periodogram: the map's variance over the periodogram's (Hann: centre-weighted)
    // total, so that the spectrum carries the whole map's variance; 1 for the rectangular window of a periodic map.
    double window_scale() const override { return window_scale_; }
    const Psd2d& spectrum() const { return spectrum_; }       // the 2-D periodogram
    const RadialPsd& rings() const { return radial_; }        // its ring means
    // Independent periodogram samples of the ring holding zeta (relative standard error 1/sqrt of it).
    double ring_samples(double zeta) const;
    // Relative standard error of sigma_h for a random surface of this spectrum: half that of sigma_h^2,
    // sqrt(sum_k M_k^2 / nu_k) / sum_k M_k over the rings' variances M_k and independent samples nu_k, counted as the
    // rectangular window's whatever the window (sigma_h is the window-corrected, unweighted rms: docs/HEIGHTMAPS.md).
    double sigma_relative_error() const override;

private:
    bool periodic_ = false;
    double map_rms_ = 0, band_scale_ = 1, window_scale_ = 1;
    std::size_t skipped_rings_ = 0;
    Psd2d spectrum_;
    RadialPsd radial_;
    std::shared_ptr<const MapRingPsd> rings_psd_;   // the ring means as a PSD, rolled off beyond the band
    double inverse_variance_ = 0, nyquist_ = 0;
};

// The mean of the 8 bins around DC of a periodogram (its lowest ring on the lattice): what MapStatistics puts in the
// DC bin, where removing the mean left 0 (or the Hann window's leakage). Error below 3 x 3 bins.
double lowest_ring_mean(const Psd2d& spectrum);

}  // namespace surfscatter::surface
