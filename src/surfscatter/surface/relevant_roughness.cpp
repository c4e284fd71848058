#include "surfscatter/surface/relevant_roughness.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::surface {

double visible_disc_mass(const RadialStatistics& stats, double theta_i_rad, double lambda_nm) {
    require_positive(lambda_nm, "wavelength");
    require_finite(theta_i_rad, "incidence angle");
    const double k = wavenumber_per_um(lambda_nm);
    const double s = std::clamp(std::sin(std::abs(theta_i_rad)), 0.0, 1.0);
    const double inner = stats.radial_cdf(k * (1.0 - s));
    if (s < 1e-12) return inner;
    // Annulus k(1-s) <= zeta <= k(1+s): the ring of radius zeta lies inside the disc over an arc 2 phi_max.
    // zeta = k(1 - s cos t) removes the square-root end behaviour of phi_max.
    auto integrand = [&](double t) {
        const double zeta = k * (1.0 - s * std::cos(t));
        if (zeta <= 0.0) return 0.0;
        const double q = zeta / k;
        const double c = std::clamp((q * q + s * s - 1.0) / (2.0 * q * s), -1.0, 1.0);
        const double phi_max = std::acos(c);
        return phi_max / kPi * stats.psd_unit(zeta) * 2.0 * kPi * zeta * k * s * std::sin(t);
    };
    // The lobe near zeta = 0 can be narrow against k; split at the angle where zeta reaches a few 1/L.
    const double l = stats.correlation_length();
    const double zeta_knee = std::min(k * (1.0 + s), k * (1.0 - s) + 20.0 / l);
    const double t_knee = std::acos(std::clamp((1.0 - zeta_knee / k) / s, -1.0, 1.0));
    // A jump of P-hat (sharp cut) inside the annulus is a panel edge too.
    std::vector<double> edges{0.0, t_knee, kPi};
    const double jump = stats.psd_jump_radius();
    if (jump > k * (1.0 - s) && jump < k * (1.0 + s)) edges.push_back(std::acos(std::clamp((1.0 - jump / k) / s, -1.0, 1.0)));
    std::sort(edges.begin(), edges.end());
    double annulus = 0.0;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e)
        annulus += math::integrate_adaptive(integrand, edges[e], edges[e + 1], 1e-11, 1e-14);
    return std::clamp(inner + annulus, 0.0, 1.0);
}

double relevant_roughness(const RadialStatistics& stats, double theta_i_rad, double lambda_nm) {
    return stats.sigma_h() * std::sqrt(visible_disc_mass(stats, theta_i_rad, lambda_nm));
}

}  // namespace surfscatter::surface
