#include "surfscatter/bsdf/wedge_sampling.hpp"

#include <cmath>

namespace surfscatter::bsdf {

double wedge_half_angle(double q, double s) {
    if (q <= 1.0 - s) return kPi;
    if (q >= 1.0 + s) return 0.0;
    const double c = (q * q + s * s - 1.0) / (2.0 * q * s);
    return std::acos(std::clamp(c, -1.0, 1.0));
}

std::optional<Vec3> wedge_direction(const Vec3& wi, double q, double u) {
    const double s = sin_theta(wi);
    const double phi_max = wedge_half_angle(q, s);
    if (!(phi_max > 0)) return std::nullopt;
    const double phi_i = s > 0 ? std::atan2(wi.y, wi.x) : 0.0;
    const double phi = phi_i + (2.0 * u - 1.0) * phi_max;
    const double ox = q * std::cos(phi) - wi.x, oy = q * std::sin(phi) - wi.y;
    const double z2 = 1.0 - ox * ox - oy * oy;
    if (!(z2 > 0)) return std::nullopt;
    return Vec3(ox, oy, std::sqrt(z2));
}

double wedge_pdf(double k, double cos_theta_o, double density_2d, double phi_max) {
    if (!(phi_max > 0) || cos_theta_o <= 0) return 0.0;
    return k * k * cos_theta_o * kPi * density_2d / phi_max;
}

}  // namespace surfscatter::bsdf
