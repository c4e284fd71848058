#include "surfscatter/bsdf/rayleigh_rice.hpp"

#include <cmath>

namespace surfscatter::bsdf {

namespace {
// cos and sin of the outgoing azimuth relative to the specular plane: cos(phi) = -cos(phi_o - phi_i).
void relative_azimuth(const Vec3& wi, const Vec3& wo, double& c, double& s) {
    const double si = sin_theta(wi), so = sin_theta(wo);
    if (si == 0 || so == 0) {
        c = 1;  // azimuth undefined; the unpolarised sum does not depend on it there
        s = 0;
        if (si == 0 && so > 0) {
            c = -wo.x / so;  // measure from +x, the arbitrary plane of incidence at normal incidence
            s = -wo.y / so;
        }
        return;
    }
    // phi_o - phi_i via dot and cross of the projected directions.
    const double cd = (wi.x * wo.x + wi.y * wo.y) / (si * so);
    const double sd = (wi.x * wo.y - wi.y * wo.x) / (si * so);
    c = -cd;
    s = sd;
}
}  // namespace

double rayleigh_rice_q(const Vec3& wi, const Vec3& wo, std::complex<double> eps) {
    double c, s;
    relative_azimuth(wi, wo, c, s);
    const double ci = wi.z, co = wo.z;
    const double si2 = sin2_theta(wi), so2 = sin2_theta(wo);
    const std::complex<double> ri = std::sqrt(eps - si2), ro = std::sqrt(eps - so2);
    const std::complex<double> qss = (eps - 1.0) * c / ((ci + ri) * (co + ro));
    const std::complex<double> qsp = (eps - 1.0) * ro * s / ((ci + ri) * (eps * co + ro));
    const std::complex<double> qps = (eps - 1.0) * ri * s / ((eps * ci + ri) * (co + ro));
    const std::complex<double> qpp =
        (eps - 1.0) * (ri * ro * c - eps * std::sqrt(si2 * so2)) / ((eps * ci + ri) * (eps * co + ro));
    return 0.5 * (std::norm(qss) + std::norm(qsp) + std::norm(qps) + std::norm(qpp));
}

double rayleigh_rice_q_perfect(const Vec3& wi, const Vec3& wo) {
    double c, s;
    relative_azimuth(wi, wo, c, s);
    const double ci = wi.z, co = wo.z;
    if (ci <= 0 || co <= 0) return 0.0;
    const double qss = c, qsp = s / co, qps = s / ci;
    const double qpp = (c - std::sqrt(sin2_theta(wi) * sin2_theta(wo))) / (ci * co);
    return 0.5 * (qss * qss + qsp * qsp + qps * qps + qpp * qpp);
}

}  // namespace surfscatter::bsdf
