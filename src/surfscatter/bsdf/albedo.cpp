#include "surfscatter/bsdf/albedo.hpp"

#include <cmath>

#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

DirectionalAlbedo directional_albedo(const Bsdf& bsdf, double theta_i_rad, double lambda_nm) {
    const double s = std::sin(theta_i_rad), ci = std::cos(theta_i_rad);
    const Vec3 wi(s, 0.0, ci);
    // q, phi about the specular point, phi from the azimuth of i: o_xy = q (cos phi, sin phi) - i_xy.
    const DiscIntegral c = integrate_disc_adaptive(s, ci, [&](double q, double phi, double cos2_theta_o) {
        return bsdf.eval(wi, Vec3(q * std::cos(phi) - s, q * std::sin(phi), std::sqrt(cos2_theta_o)), lambda_nm);
    }, 1e-7, bsdf.jump_radius(lambda_nm));
    DirectionalAlbedo a{c.value, bsdf.delta_reflectance(wi, lambda_nm), c.error, c.evaluations};
    if (!std::isfinite(a.scatter) || !std::isfinite(a.error) || !std::isfinite(a.specular))
        fail("albedo of {} at theta_i {} deg, {} nm is not finite", bsdf.name(), theta_i_rad / kDegree, lambda_nm);
    return a;
}

}  // namespace surfscatter::bsdf
