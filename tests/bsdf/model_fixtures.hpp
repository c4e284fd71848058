#pragma once
// Small helpers shared by the bsdf tests: model options for analytic surfaces and hemisphere quadrature.
#include <cmath>
#include <memory>

#include "surfscatter/bsdf/factory.hpp"

namespace surfscatter::bsdf::test {

inline ModelOptions kc_options(ModelKind model, double sigma, double length, double gamma) {
    ModelOptions o;
    o.model = model;
    o.surface.psd = PsdKind::kc;
    o.surface.sigma = sigma;
    o.surface.corr_length = length;
    o.surface.gamma = gamma;
    return o;
}

// sigma giving g0 = (2 k sigma cos theta_i)^2 = g (with sigma_h; sigma_rel is a little smaller).
inline double sigma_for_g(double g, double lambda_nm, double theta_i_deg) {
    const double k = 2 * 3.14159265358979323846 / (lambda_nm * 1e-3);
    return std::sqrt(g) / (2 * k * std::cos(theta_i_deg * 3.14159265358979323846 / 180));
}

// Directional albedo: integral of f cos over the hemisphere (Gauss-Legendre in cos theta_o with points clustered
// toward the specular cone by splitting at cos theta_i, uniform midpoint in phi) plus the delta reflectance.
inline double directional_albedo(const Bsdf& bsdf, const Vec3& wi, double lambda_nm, int n_theta = 400,
                                 int n_phi = 512) {
    // Composite midpoint in theta (fine) and phi; the lobes used in tests are broader than a few cells.
    double sum = 0;
    const double dt = 0.5 * kPi / n_theta, dp = kTwoPi / n_phi;
    for (int i = 0; i < n_theta; ++i) {
        const double theta = (i + 0.5) * dt;
        const double st = std::sin(theta), ct = std::cos(theta);
        for (int j = 0; j < n_phi; ++j) {
            const double phi = (j + 0.5) * dp;
            const Vec3 wo(st * std::cos(phi), st * std::sin(phi), ct);
            sum += bsdf.eval(wi, wo, lambda_nm) * ct * st;
        }
    }
    return sum * dt * dp + bsdf.delta_reflectance(wi, lambda_nm);
}

}  // namespace surfscatter::bsdf::test
