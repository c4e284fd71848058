#pragma once
// Slope variances of an elliptical surface seen through an isotropic Gaussian smoothing of std s (THEORY 4.1, 7.1):
//   <h_u^2>_s = int zeta_u^2 P-hat(zeta) e^{-s^2 |zeta|^2} d^2 zeta   (and v), times sigma^2.
// Substituting eta = (zeta_u, S zeta_v) (S = LV / LU) turns P-hat into the radial P-hat(|eta|) and the smoothing into
// e^{-s^2 |eta|^2 q(phi)}, q = cos^2 phi + sin^2 phi / S^2, so that along each azimuth phi of eta the radial
// integral is the radial statistics' own smoothed mean-square slope at the smoothing s sqrt(q(phi)):
//   <h_u^2>_s = (1 / 2 pi) int_0^{2 pi} cos^2 phi M(s sqrt(q)) d phi,  <h_v^2>_s = (1 / 2 pi S^2) int sin^2 phi M(..),
// M(s') = radial.mean_square_slope(s', no cutoff) (closed forms for KC and Gaussian). s = 0 gives
// slope_variances_lay(). Accuracy: the azimuth integral is adaptive to 1e-10 relative; tests/surface measure it
// against a direct 2-D quadrature of the elliptical PSD (1e-6) and the elliptical Gaussian's closed form (1e-9).
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"

namespace surfscatter::surface {

// (<h_u^2>_s, <h_v^2>_s), dimensionless; +inf where the radial one diverges (s = 0 and KC gamma <= 3).
// smoothing_um >= 0 (Error otherwise).
Vec2 smoothed_slope_variances_lay(const EllipticalStatistics& statistics, double smoothing_um);

}  // namespace surfscatter::surface
