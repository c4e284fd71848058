#include "surfscatter/material/fresnel.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::material {

FresnelSP fresnel_conductor_sp(double cos_theta_i, std::complex<double> eta) {
    if (!(cos_theta_i >= -1e-9) || !(cos_theta_i <= 1.0 + 1e-9))
        fail("Fresnel: incidence cosine must lie in [0, 1], got {}", cos_theta_i);
    if (!std::isfinite(eta.real()) || !std::isfinite(eta.imag()) || eta.imag() < 0)
        fail("Fresnel: index must be finite with k >= 0, got {} + {}i", eta.real(), eta.imag());
    const double c = std::clamp(cos_theta_i, 0.0, 1.0);
    const double sin2 = 1.0 - c * c;
    const std::complex<double> eta2 = eta * eta;
    // w = eta cos(theta_t) from Snell's law; Im(eta^2 - sin^2) = 2nk >= 0, so the principal root is the
    // transmitted wave that decays into the metal.
    const std::complex<double> w = std::sqrt(eta2 - sin2);
    const std::complex<double> rs = (c - w) / (c + w);
    const std::complex<double> rp = (eta2 * c - w) / (eta2 * c + w);
    FresnelSP r{std::norm(rs), std::norm(rp)};
    // eta = 1 at grazing incidence is 0/0: the limit is total reflection.
    if (!std::isfinite(r.rs)) r.rs = 1.0;
    if (!std::isfinite(r.rp)) r.rp = 1.0;
    return r;
}

double fresnel_conductor(double cos_theta_i, std::complex<double> eta) {
    return fresnel_conductor_sp(cos_theta_i, eta).unpolarized();
}

}  // namespace surfscatter::material
