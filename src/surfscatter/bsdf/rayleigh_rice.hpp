#pragma once
// Rayleigh-Rice polarisation factor for unpolarised light (THEORY 1.3 item 2): Q = 1/2 sum |Q_ij|^2 with the
// HP17 / Church Q_ss, Q_sp, Q_ps, Q_pp. We keep the 1/2 (the unpolarised average), so that Q equals the Fresnel
// reflectance R(theta_i) in the specular direction; the HP17 reference code omits it (Q = 2R there).
#include <complex>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

// eps = (n + i k)^2 relative permittivity of the conductor.
double rayleigh_rice_q(const Vec3& wi, const Vec3& wo, std::complex<double> eps);
// The limit eps -> infinity (perfect conductor).
double rayleigh_rice_q_perfect(const Vec3& wi, const Vec3& wo);

}  // namespace surfscatter::bsdf
