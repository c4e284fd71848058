#pragma once
// Relevant roughness (THEORY.md 1.1, 2.1): the part of the PSD inside the visible disc |zeta/k - i_xy| <= 1,
// k = 2 pi / lambda. lambda in nm, lengths in um, angles in radians.
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

// Angular wavenumber 2 pi / lambda in rad/um for lambda in nm.
inline double wavenumber_per_um(double lambda_nm) { return 2.0 * 3.14159265358979323846 * 1000.0 / lambda_nm; }

// M_disc = sigma_rel^2 / sigma_h^2 = mass of P-hat inside the disc of radius k centred at k sin(theta_i): closed
// radial CDF inside |zeta| <= k(1 - s), plus the annulus k(1-s)..k(1+s) weighted by phi_max/pi (Gauss-Legendre on
// zeta = k(1 - s cos t)). Relative accuracy ~1e-10 (tested against 2-D brute force). theta_i in [0, pi/2].
double visible_disc_mass(const RadialStatistics&, double theta_i_rad, double lambda_nm);
double relevant_roughness(const RadialStatistics&, double theta_i_rad, double lambda_nm);  // sigma_rel, um

}  // namespace surfscatter::surface
