#pragma once
// Exact Fresnel reflectance of a conductor (complex index) for s and p polarisation and unpolarised light, and of
// a dielectric interface (real index) with the refraction it implies.
#include <cmath>
#include <complex>

namespace surfscatter::material {

template <typename Real>
struct FresnelPolarised {
    Real rs = 0;  // |r_s|^2
    Real rp = 0;  // |r_p|^2
    Real unpolarized() const { return Real(0.5) * (rs + rp); }
};
using FresnelSP = FresnelPolarised<double>;

// cos_theta_i in [0, 1] (clamped only against round-off above 1); eta = n + i k relative to the outside medium.
FresnelSP fresnel_conductor_sp(double cos_theta_i, std::complex<double> eta);

// fresnel_conductor_sp without the argument checks (c in [0, 1], k >= 0, both finite), in real arithmetic: no
// complex division or library call, so that loops over wavelengths inline and vectorise it (Real = float gives four
// wavelengths per SSE instruction; its error is measured in tests/material/test_fresnel.cpp). The same formula:
// w = eta cos(theta_t) = sqrt(eta^2 - sin^2) (principal root, taken without cancellation), r_s = (c - w) / (c + w),
// r_p = (eta^2 c - w) / (eta^2 c + w). A 0/0 (eta = 1 at grazing incidence) or an overflow is total reflection.
template <typename Real>
inline FresnelPolarised<Real> fresnel_conductor_sp_unchecked(Real c, Real n, Real k) {
    const Real eta2_re = n * n - k * k, eta2_im = Real(2) * n * k;
    const Real x = eta2_re - (Real(1) - c * c);  // eta^2 - sin^2 = x + i eta2_im
    const Real modulus = std::sqrt(x * x + eta2_im * eta2_im);
    const Real large = std::sqrt(Real(0.5) * (modulus + std::abs(x)));  // the larger of |Re w|, |Im w|
    const Real quotient = std::abs(eta2_im) / (Real(2) * large);  // computed always: selects, not branches
    const Real small = large > 0 ? quotient : Real(0);
    // w = a + i b, principal root: a >= 0, b of the sign of eta2_im.
    const bool x_positive = x >= 0;
    const Real a = x_positive ? large : small, b = std::copysign(x_positive ? small : large, eta2_im);
    // Both ratios are in [0, 1] up to round-off; NaN (0/0) and Inf (overflow) fail the test and give 1.
    const auto ratio = [](Real num, Real den) {
        const Real r = num / den;
        return r <= Real(2) ? r : Real(1);
    };
    const Real p = eta2_re * c, q = eta2_im * c;  // eta^2 c
    return {ratio((c - a) * (c - a) + b * b, (c + a) * (c + a) + b * b),
            ratio((p - a) * (p - a) + (q - b) * (q - b), (p + a) * (p + a) + (q + b) * (q + b))};
}
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
