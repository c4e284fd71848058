#include "surfscatter/bsdf/albedo.hpp"

#include <cmath>

#include "surfscatter/bsdf/wedge_sampling.hpp"

namespace surfscatter::bsdf {

DirectionalAlbedo directional_albedo(const Bsdf& bsdf, double theta_i_rad, double lambda_nm) {
    const double s = std::sin(theta_i_rad);
    const Vec3 wi(s, 0.0, std::cos(theta_i_rad));
    DirectionalAlbedo a;
    // q = o_xy + i_xy: polar about the specular point; f d^2 o_xy = f cos(theta_o) d omega.
    a.scatter = integrate_visible_disc(s, 1e-7, [&](double q, double phi) {
        const double ox = q * std::cos(phi) - s, oy = q * std::sin(phi);
        const double z2 = 1.0 - ox * ox - oy * oy;
        return z2 > 0 ? bsdf.eval(wi, Vec3(ox, oy, std::sqrt(z2)), lambda_nm) : 0.0;
    });
    a.specular = bsdf.delta_reflectance(wi, lambda_nm);
    return a;
}

}  // namespace surfscatter::bsdf
