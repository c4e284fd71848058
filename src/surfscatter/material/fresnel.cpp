#include "surfscatter/material/fresnel.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::material {

FresnelSP fresnel_conductor_sp(double cos_theta_i, std::complex<double> eta) {
    if (!(cos_theta_i >= -1e-9) || !(cos_theta_i <= 1.0 + 1e-9))
        fail("Fresnel: incidence cosine must lie in [0, 1], got {}", cos_theta_i);
    if (!std::isfinite(eta.real()) || !std::isfinite(eta.imag()) || eta.imag() < 0)
        fail("Fresnel: index must be finite with k >= 0, got {} + {}i", eta.real(), eta.imag());
    return fresnel_conductor_sp_unchecked(std::clamp(cos_theta_i, 0.0, 1.0), eta.real(), eta.imag());
}

double fresnel_conductor(double cos_theta_i, std::complex<double> eta) {
    return fresnel_conductor_sp(cos_theta_i, eta).unpolarized();
}

DielectricFresnel fresnel_dielectric(double cos_theta_i, double eta) {
    if (!(eta > 0) || !std::isfinite(eta)) fail("Fresnel: dielectric index ratio must be positive, got {}", eta);
    DielectricFresnel f;
    const bool outside = cos_theta_i >= 0;
    f.eta_it = outside ? eta : 1 / eta;
    f.eta_ti = outside ? 1 / eta : eta;
    const double c_i = std::min(std::abs(cos_theta_i), 1.0);
    const double sin2_t = f.eta_ti * f.eta_ti * (1 - c_i * c_i);
    if (sin2_t >= 1) return f;  // total internal reflection
    const double c_t = std::sqrt(1 - sin2_t);
    // Amplitudes for s and p polarisation (Born & Wolf 1.5.2), indices relative to the incident medium.
    const double rs = (c_i - f.eta_it * c_t) / (c_i + f.eta_it * c_t);
    const double rp = (f.eta_it * c_i - c_t) / (f.eta_it * c_i + c_t);
    f.reflectance = 0.5 * (rs * rs + rp * rp);
    f.cos_theta_t = outside ? -c_t : c_t;
    return f;
}

double fresnel_diffuse_reflectance(double eta) {
    static const math::GaussLegendreRule rule(64);
    const std::vector<double>& nodes = rule.nodes;
    const std::vector<double>& weights = rule.weights;
    // The integrand has a kink at the critical cosine (eta < 1): integrate the two sides separately.
    const double critical = eta < 1 ? std::sqrt(1 - eta * eta) : 0.0;
    double total = 0;
    for (const auto& [a, b] : {std::pair{0.0, critical}, std::pair{critical, 1.0}}) {
        if (!(b > a)) continue;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            const double mu = 0.5 * (a + b) + 0.5 * (b - a) * nodes[k];
            total += weights[k] * 0.5 * (b - a) * fresnel_dielectric(mu, eta).reflectance * mu;
        }
    }
    return 2 * total;
}

}  // namespace surfscatter::material
