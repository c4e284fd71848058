#pragma once
// Exact Fresnel reflectance of a conductor (complex index) for s and p polarisation and unpolarised light.
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

}  // namespace surfscatter::material
