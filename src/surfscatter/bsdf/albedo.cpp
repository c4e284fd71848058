#include "surfscatter/bsdf/albedo.hpp"

#include <cmath>

#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

DirectionalAlbedo directional_albedo(const Bsdf& bsdf, double theta_i_rad, double lambda_nm, double phi_i_rad) {
    require_finite(phi_i_rad, "incidence azimuth");
    const double s = std::sin(theta_i_rad), ci = std::cos(theta_i_rad);
    const bool isotropic = bsdf.isotropic();
    const double cp = isotropic ? 1.0 : std::cos(phi_i_rad), sp = isotropic ? 0.0 : std::sin(phi_i_rad);
    const Vec3 wi(s * cp, s * sp, ci);
    // q, phi about the specular point, phi from the azimuth of i: o_xy = q (cos phi, sin phi) - i_xy in the frame of i.
    auto at = [&](double x, double y, double z) {
        return bsdf.eval(wi, Vec3(cp * x - sp * y, sp * x + cp * y, z), lambda_nm);
    };
    const DiscIntegral c = integrate_disc_adaptive(s, ci, [&](double q, double phi, double cos2_theta_o) {
        const double x = q * std::cos(phi) - s, y = q * std::sin(phi), z = std::sqrt(cos2_theta_o);
        return isotropic ? at(x, y, z) : 0.5 * (at(x, y, z) + at(x, -y, z));
    }, 1e-7, bsdf.jump_radius(lambda_nm));
    DirectionalAlbedo a{c.value, bsdf.delta_reflectance(wi, lambda_nm), c.error, c.evaluations};
    if (!std::isfinite(a.scatter) || !std::isfinite(a.error) || !std::isfinite(a.specular))
        fail("albedo of {} at theta_i {} deg, {} nm is not finite", bsdf.name(), theta_i_rad / kDegree, lambda_nm);
    return a;
}

}  // namespace surfscatter::bsdf
