#pragma once
// Geometry shared by every wave-optical lobe (THEORY 0 and 2.6): the scattering vector zeta = k (i_xy + o_xy)
// (rad/um), the visible disc |zeta/k - i_xy| <= 1 of propagating directions, and the azimuthal-wedge sampler of the
// supplemental's eqs 5-7: for a radius |zeta| drawn from an isotropic 2-D density, the azimuth is uniform over the
// part of the circle |zeta| that lies inside the disc, phi_i +- phi_max(|zeta|).
#include <cmath>
#include <functional>
#include <optional>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

// Wavenumber in rad/um for a wavelength in nm.
inline double wavenumber(double lambda_nm) { return kTwoPi / (lambda_nm * 1e-3); }

// phi_max in [0, pi] for the normalised radius q = |zeta|/k and s = sin(theta_i): pi inside the inner circle
// q <= 1 - s, 0 beyond q >= 1 + s.
double wedge_half_angle(double q, double sin_theta_i);

// |i_xy + o_xy| (= |zeta| / k).
inline double scatter_radius(const Vec3& wi, const Vec3& wo) {
    const double x = wi.x + wo.x, y = wi.y + wo.y;
    return std::sqrt(x * x + y * y);  // not hypot: no overflow is possible here, and sqrt is twice as fast
}

// Outgoing direction for the normalised radius q and wedge position u in [0, 1) (eq 6: phi = phi_i + (2u-1) phi_max;
// eq 7: o_xy = q (cos phi, sin phi) - i_xy). Nothing if it falls on or below the horizon.
std::optional<Vec3> wedge_direction(const Vec3& wi, double q, double u);

// Solid-angle pdf of such a direction when |zeta| was drawn with the isotropic 2-D density `density_2d` (per
// (rad/um)^2, already divided by the mass of its truncation to the disc): k^2 cos(theta_o) pi density / phi_max.
double wedge_pdf(double k, double cos_theta_o, double density_2d, double phi_max);

// Integral over the visible disc {|q - i_xy| <= 1} of f(q, phi) d^2q, q = zeta/k in polar coordinates about 0 and
// phi measured from the azimuth of i, for integrands symmetric in phi (isotropic lobes): composite Gauss-Legendre in
// q on panels spaced in log(q) from q_lo and graded geometrically toward the circles q = 1 - s and q = 1 + s, where
// the wedge half-angle has square-root kinks; azimuth phi = phi_max (1 - (1 - t)^2), which absorbs the
// square-root behaviour of cos(theta_o) at the wedge edge. The disc q < q_lo counts as pi q_lo^2 f(0, 0). A panel
// edge at q_jump > 0 (a circle where f jumps, e.g. a sharp high-pass cut) keeps the rule accurate there.
// Relative accuracy ~1e-6 for lobes wider than a few q_lo (tested through the white furnace).
double integrate_visible_disc(double sin_theta_i, double q_lo, const std::function<double(double q, double phi)>& f,
                              double q_jump = 0.0);

}  // namespace surfscatter::bsdf
