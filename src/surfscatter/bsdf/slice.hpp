#pragma once
// Tables of a model for plots, as `surfscatter brdf slice` and a study's BRDF jobs write them (CSV, full precision).
#include <ostream>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"

namespace surfscatter::bsdf {

// In-plane slices: rows model,theta_i,theta_o_signed,brdf,specular for each incidence angle (degrees), theta_o from
// -89.5 to 89.5 degrees in 0.25 degree steps, positive on the specular side (phi_o = phi_i + 180); `specular` is
// the delta lobe's reflectance. `header` writes the header line first.
// The slices' outgoing angles (theta_o_signed, degrees) and the direction of one for incidence azimuth phi_i_deg.
std::vector<double> slice_angles();
Vec3 slice_direction(double theta_o_signed_deg, double phi_i_deg);

void write_slice_csv(std::ostream& out, const std::string& name, const Bsdf& model, const std::vector<double>& theta_i_deg,
                     double phi_i_deg, double lambda_nm, bool header);

// Directional albedo: rows model,theta_i,albedo,scatter,specular,phi_i_deg (bsdf/albedo.hpp) for each incidence
// azimuth (degrees) and, within it, each incidence angle.
void write_albedo_csv(std::ostream& out, const std::string& name, const Bsdf& model, const std::vector<double>& theta_i_deg,
                      const std::vector<double>& phi_i_deg, double lambda_nm, bool header);

// The incidence azimuths at which a study tabulates the albedo of `model`: phi_i_deg alone for an isotropic model (its
// albedo does not depend on the azimuth), else phi_i_deg + 15 k deg, k = 0 .. 11. An elliptical surface's statistics
// are point-symmetric (C(r) = C(-r)), so its albedo repeats after 180 deg; 15 deg steps resolve its cos(2 (phi - A))
// variation about any lay angle A with 12 evaluations per incidence angle (docs/DISTRIBUTED.md).
std::vector<double> albedo_azimuths(const Bsdf& model, double phi_i_deg);

}  // namespace surfscatter::bsdf
