#pragma once
// Directional albedo of an isotropic BSDF: the integral of f cos(theta_o) over the hemisphere (= the integral of f
// over the disc of projected directions, integrate_visible_disc about the specular point) and the delta lobe.
#include "surfscatter/bsdf/bsdf.hpp"

namespace surfscatter::bsdf {

struct DirectionalAlbedo {
    double scatter = 0;   // continuous part
    double specular = 0;  // delta part
    double total() const { return scatter + specular; }
};

DirectionalAlbedo directional_albedo(const Bsdf& bsdf, double theta_i_rad, double lambda_nm);

}  // namespace surfscatter::bsdf
