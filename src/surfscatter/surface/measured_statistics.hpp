#pragma once
// What `--psd measured` reads of a measured surface, whether a map (map_statistics.hpp) or a profile taken as an
// isotropic surface (profile_statistics.hpp): an isotropic P(zeta) within the band the measurement resolves, and the
// figures the models report about it.
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

class MeasuredStatistics : public RadialStatistics {
public:
    virtual double map_rms() const = 0;       // rms of the prepared map or profile, um
    virtual double first_ring() const = 0;    // rad/um: the lowest non-zero frequency resolved
    virtual double ring_width() const = 0;    // rad/um: the frequency resolution (2 pi / the map's side or profile's length)
    virtual double nyquist() const = 0;       // top of the band, rad/um
    // Relative standard error of sigma_h for a random surface of this spectrum (half that of sigma_h^2).
    virtual double sigma_relative_error() const = 0;
    // The window correction on the periodogram (the measurement's variance over the windowed periodogram's total).
    virtual double window_scale() const = 0;
    double below_band_fraction() const { return radial_cdf(0.5 * ring_width()); }  // of sigma_h^2, continued
    double above_band_fraction() const { return 1.0 - radial_cdf(nyquist()); }      // of sigma_h^2, rolled off
};

}  // namespace surfscatter::surface
