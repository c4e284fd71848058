#pragma once
// Lateral statistics of a measured height map from its areal autocovariance (ACV), over valid points only.
//
// ACV: C^(t) = sum_n (m h)_n (m h)_(n+t) / sum_n m_n m_(n+t) for every lag t (linear correlation by zero-padded FFT,
// m = 1 at valid points): each lag's mean over the pairs of valid points it has, an unbiased estimate of C(t) for
// any mask (no fill values). The normalised ACF is C^(t) / C^(0). Lags farther than half the map along either
// axis are not used (fewer than half the pairs, and the form removal bends them).
//
// * Texture aspect ratio Str (ISO 25178-2): along each direction theta (0.5 degree steps over 180 degrees, the
//   ACF being point-symmetric) the distance r(theta) at which the ACF first falls to s = 0.2 (bilinear in the lag
//   grid, linear between radial steps of a quarter pixel); Sal = min r (the autocorrelation length), Str =
//   min r / max r: 1 for an isotropic surface, near 0 for a strongly directional one (grinding, rolling, turning
//   marks). If along some direction the ACF stays above 0.2 out to the edge of the usable lags, that r is the
//   edge distance and Str is an upper bound (`str_is_bound`).
// * Correlation length: the distance at which the azimuthal mean of the ACF first falls to 1/e (the l of a
//   Gaussian ACV exp(-r^2/l^2), the L of an exponential one); half the shorter side if it never does. The mean
//   (form) removal makes every ACF estimate of a finite patch fall too early: the ACF of a patch only a few
//   correlation lengths wide reads short (see kMinWidthInCorrelationLengths).
#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::surface {

struct AcvMeasures {
    double correlation_length_um = 0.0;
    double autocorrelation_length_um = 0.0;    // Sal (s = 0.2)
    double texture_aspect_ratio = 0.0;         // Str (s = 0.2)
    bool str_is_bound = false;                 // the ACF did not fall to 0.2 along some direction: an upper bound
    double slowest_direction_deg = 0.0;        // direction of max r(theta) from +x towards +y (the texture's lay)
};

// Of a map whose form is already removed (heightmap/form.hpp).
AcvMeasures acv_measures(const heightmap::HeightMap& flat);

// A correlation length longer than this fraction of the map's shorter side is reported with a warning: the patch
// is too small to measure it (its ACF falls early, see above).
inline constexpr double kMaxCorrelationLengthFraction = 0.1;

// Threshold of ISO 25178-2's Sal and Str.
inline constexpr double kAcfThreshold = 0.2;

}  // namespace surfscatter::surface
