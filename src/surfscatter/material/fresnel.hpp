#pragma once
// Exact Fresnel reflectance of a conductor (complex index) for s and p polarisation and unpolarised light, and of
// a dielectric interface (real index) with the refraction it implies.
#include <complex>

namespace surfscatter::material {

struct FresnelSP {
    double rs = 0;  // |r_s|^2
    double rp = 0;  // |r_p|^2
    double unpolarized() const { return 0.5 * (rs + rp); }
};

// cos_theta_i in [0, 1] (clamped only against round-off above 1); eta = n + i k relative to the outside medium.
FresnelSP fresnel_conductor_sp(double cos_theta_i, std::complex<double> eta);
double fresnel_conductor(double cos_theta_i, std::complex<double> eta);

// Dielectric interface of relative index eta = n_inside / n_outside (> 0), seen at incidence cosine cos_theta_i
// relative to the normal (which points outside); cos_theta_i < 0 means the light arrives from inside. As
// Mitsuba's fresnel(): the unpolarised reflectance, the cosine of the refracted direction (sign opposite to
// cos_theta_i; 0 under total internal reflection, where reflectance = 1), and the relative indices across the
// interface along the ray (eta_it) and back (eta_ti = 1 / eta_it).
struct DielectricFresnel {
    double reflectance = 1;
    double cos_theta_t = 0;
    double eta_it = 1;
    double eta_ti = 1;
};
DielectricFresnel fresnel_dielectric(double cos_theta_i, double eta);

// Hemispherical average of the reflectance, 2 int_0^1 F(mu) mu dmu, for light arriving from outside an interface
// of relative index eta (eta < 1: from the denser side, total internal reflection included). Gauss-Legendre
// quadrature on both sides of the critical angle, accurate to ~1e-12.
double fresnel_diffuse_reflectance(double eta);

}  // namespace surfscatter::material
