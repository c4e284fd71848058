#pragma once
// Directional albedo of an isotropic BSDF: the integral of f cos(theta_o) over the hemisphere (= the integral of f
// over the disc of projected directions o_xy) plus the delta lobe. The disc integral follows the lobe about the
// specular point (integrate_disc_adaptive, wedge_sampling.hpp: every model's lobe is centred there, GHS, SSA and the
// two-scale micro part as functions of k |i_xy + o_xy|, GGX through its half-vector slope |i_xy + o_xy| / (cos i +
// cos o)) to a relative error estimate of 1e-7.
// Accuracy (Albedo.* in tests/bsdf/test_albedo.cpp, against nested adaptive quadrature in (theta_o, phi_o) and GGX's
// slope-space integral, both written in the test): within 1e-4 of the reference for every model, GGX alpha 1e-4 to 1,
// theta_i 0 to 89.99 deg; `error` is the integrator's own estimate (docs/MODELS.md gives the measured errors).
#include "surfscatter/bsdf/bsdf.hpp"

namespace surfscatter::bsdf {

struct DirectionalAlbedo {
    double scatter = 0;    // continuous part
    double specular = 0;   // delta part
    double error = 0;      // estimated absolute error of scatter
    long evaluations = 0;  // BSDF evaluations the integral took
    double total() const { return scatter + specular; }
};

// At incidence (theta_i, phi_i); phi_i matters only for a BSDF that is not isotropic(), whose integrand is then the
// mean of the two halves of the disc, phi and -phi about the incidence plane (the same cubature).
DirectionalAlbedo directional_albedo(const Bsdf& bsdf, double theta_i_rad, double lambda_nm, double phi_i_rad = 0.0);

}  // namespace surfscatter::bsdf
