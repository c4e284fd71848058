#include "surfscatter/bsdf/slice.hpp"

#include <cmath>

#include <fmt/format.h>

#include "surfscatter/bsdf/albedo.hpp"

namespace surfscatter::bsdf {

namespace {
std::string number(double v) { return fmt::format("{:.10g}", v); }
Vec3 direction(double theta_deg, double phi_deg) { return spherical_direction(theta_deg * kDegree, phi_deg * kDegree); }
}  // namespace

std::vector<double> slice_angles() {
    std::vector<double> angles;
    for (int j = -1790; j <= 1790; j += 5) angles.push_back(0.05 * j);
    return angles;
}

Vec3 slice_direction(double theta_o_signed_deg, double phi_i_deg) {
    return direction(std::abs(theta_o_signed_deg), phi_i_deg + (theta_o_signed_deg >= 0 ? 180.0 : 0.0));
}

void write_slice_csv(std::ostream& out, const std::string& name, const Bsdf& model, const std::vector<double>& theta_i_deg,
                     double phi_i_deg, double lambda_nm, bool header) {
    if (header) out << "model,theta_i,theta_o_signed,brdf,specular\n";
    for (const double ti : theta_i_deg) {
        const Vec3 wi = direction(ti, phi_i_deg);
        const double specular = model.delta_reflectance(wi, lambda_nm);
        for (const double t : slice_angles())
            out << name << ',' << number(ti) << ',' << number(t) << ','
                << number(model.eval(wi, slice_direction(t, phi_i_deg), lambda_nm)) << ',' << number(specular) << '\n';
    }
}

void write_albedo_csv(std::ostream& out, const std::string& name, const Bsdf& model, const std::vector<double>& theta_i_deg,
                      const std::vector<double>& phi_i_deg, double lambda_nm, bool header) {
    if (header) out << "model,theta_i,albedo,scatter,specular,phi_i_deg\n";
    for (const double phi : phi_i_deg)
        for (const double ti : theta_i_deg) {
            const DirectionalAlbedo a = directional_albedo(model, ti * kDegree, lambda_nm, phi * kDegree);
            out << name << ',' << number(ti) << ',' << number(a.total()) << ',' << number(a.scatter) << ','
                << number(a.specular) << ',' << number(phi) << '\n';
        }
}

std::vector<double> albedo_azimuths(const Bsdf& model, double phi_i_deg) {
    if (model.isotropic()) return {phi_i_deg};
    constexpr int kSteps = 12;  // 15 deg over [0, 180)
    std::vector<double> azimuths;
    for (int k = 0; k < kSteps; ++k) azimuths.push_back(phi_i_deg + 180.0 * k / kSteps);
    return azimuths;
}

}  // namespace surfscatter::bsdf
