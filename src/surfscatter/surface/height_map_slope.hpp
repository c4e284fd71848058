#pragma once
// Slopes of a measured height map (THEORY.md 4.1, 4.2): the rms slope sqrt<|grad h|^2> that sets a Beckmann alpha
// (alpha_B = rms slope) and, by convention, the GGX alpha of `--alpha-from measured`.
//
// Gradients are central differences (h[i+1] - h[i-1]) / (2 dx) at interior points of the form-removed map whose
// four neighbours are valid. For a sinusoid of angular frequency q this measures q sin(q dx)/(q dx) instead of q:
// relative error about -(q dx)^2/6, i.e. -0.16 % at 10 samples per period. For a rough surface the rms slope is a
// property of the surface AND the resolution: for KC with gamma <= 3 it diverges as the pixel spacing goes to zero,
// so always quote the spacing (or the smoothing scale) with it.
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/form.hpp"

namespace surfscatter::surface {

// Root-mean-square slope sqrt<(dh/dx)^2 + (dh/dy)^2> of the form-removed map (dimensionless). Error if no point
// has four valid neighbours.
double rms_slope(const heightmap::HeightMap& map, heightmap::Form form = heightmap::Form::plane);

// Mean-square slopes <h_u^2>, <h_v^2> of the form-removed map along the lay axes u (at lay_angle_rad from the map's x
// towards y) and v, from the same central differences: <h_u^2> + <h_v^2> = rms_slope^2 up to round-off.
Vec2 slope_variances_lay(const heightmap::HeightMap& map, double lay_angle_rad, heightmap::Form form = heightmap::Form::plane);

// The slope covariance <g g^T> of the same gradients (xx = <(dh/dx)^2>, yy, xy), and its principal axes: the variance
// along u, the direction of least slope (along a lay's marks), and across it along v, and u's angle from x (rad).
struct SlopeCovariance {
    double xx = 0, yy = 0, xy = 0;
    struct Axes { double along_u, along_v, angle_u; };
    Axes axes() const;
};
SlopeCovariance slope_covariance(const heightmap::HeightMap& map, heightmap::Form form = heightmap::Form::plane);

// The form-removed map convolved with a Gaussian of standard deviation `smoothing_um` (transfer function
// exp(-s^2 zeta^2 / 2)), computed by FFT on the mirror-extended map (2nx x 2ny, even reflection at every edge), so
// that the borders see a continuation of the surface instead of the opposite edge. With invalid points it is the
// normalised convolution G*(m h) / G*(m) at the valid points (no fill values; invalid points stay invalid).
heightmap::HeightMap gaussian_smooth(const heightmap::HeightMap& map, double smoothing_um, heightmap::Form form = heightmap::Form::plane);

// Throws Error naming `what` unless smoothing_um is positive and no wider than the map (wider, the smoothed map
// would be flat): the check of a smoothing scale the user gives for `map`.
void require_smoothing(double smoothing_um, const heightmap::HeightMap& map, const char* what);

// rms_slope(gaussian_smooth(map, smoothing_um)): the "Gaussian smoothed" slope of THEORY.md 4.2.
double rms_slope_smoothed(const heightmap::HeightMap& map, double smoothing_um, heightmap::Form form = heightmap::Form::plane);

}  // namespace surfscatter::surface
