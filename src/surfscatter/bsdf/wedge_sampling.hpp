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

// Integral over the visible disc {|q - i_xy| <= 1} of f d^2q, q = zeta/k in polar coordinates about 0 and phi measured
// from the azimuth of i, for integrands symmetric in phi (isotropic lobes), by adaptive cubature that follows a lobe
// centred on the specular point (q = 0), however narrow, with its error estimate: q over four pieces, each in the logarithm of the distance to its end where the
// integrand is narrow or has a square-root kink: [0, q_in/2] in ln q (the lobe, down to q = 1e-12 cos^2 theta_i, the
// disc below counted as pi q^2 f(0, 0)), [q_in/2, q_in] and [q_in, 1] in ln|q - q_in| (q_in = 1 - sin theta_i, where
// the arc of radius q first meets the horizon: at grazing incidence a narrow lobe lies across it), [1, 1 + s] in
// ln(1 + s - q) (the far horizon); the azimuth phi = phi_max(q) (1 - w^2), w in [0, 1], which makes cos theta_o smooth
// at the arc's end, the starting rectangles graded in w toward the horizon down to 0.01 cos theta_i; then Genz-Malik
// cubature (math/quadrature.hpp) until the error estimate is rel_tol of the value (or 4e6 evaluations). f also gets
// cos^2 theta_o = cos^2 theta_i - q (q - 2 s cos phi) (> 0), free of the cancellation in 1 - |o_xy|^2 at grazing
// incidence. q_jump > 0: a circle where f jumps (a line of constant q here), made an edge of the starting rectangles
// (a jump between the nodes of a rectangle is invisible to its error estimate: the two-scale albedo was 3e-5 off with
// an estimate of 1e-7 before).
struct DiscIntegral {
    double value = 0, error = 0;
    long evaluations = 0;
};
DiscIntegral integrate_disc_adaptive(double sin_theta_i, double cos_theta_i,
                                     const std::function<double(double q, double phi, double cos2_theta_o)>& f,
                                     double rel_tol, double q_jump = 0.0);

}  // namespace surfscatter::bsdf
