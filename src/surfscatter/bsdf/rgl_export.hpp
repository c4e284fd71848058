#pragma once
// A scattering model tabulated in the RGL measured format (bsdf/rgl_measured.hpp), so that Mitsuba 3's and
// pbrt-v4's `measured` render it: `surfscatter brdf export`, Python `export_rgl`; accuracy in docs/MODELS.md.
//
// The parameterisation is built from the model itself: an NDF from its retro-reflection, D(m) ~ f(m, m) cos^2
// theta_m at the reference wavelength (the microfacet form f(m, m) = F G D / (4 cos^2 theta_m) read backwards; any
// positive D is valid for the format, a D close to the lobe's makes the tabulated remainder smooth), normalised so
// that int D cos = 1; sigma(wi) = int D(m) <wi, m>+ dm by quadrature; the VNDF slices D(m) <wi, m>+ / sigma(wi); the
// spectral table holds f(wi, wo) cos(theta_o) 4 sigma(wi) / D(m) at the nodes of the sample square, each node mapped
// to its half vector through the VNDF warp exactly as a reader maps it back, with the reader's own interpolated D and
// sigma (jacobian = 1), so a reader reproduces f exactly at the nodes. The coherent specular (delta) part of a model
// is not in the file (eval excludes it): delta_table() gives it for a separate smooth component.
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/rgl_measured.hpp"

namespace surfscatter::bsdf {

struct RglExportOptions {
    bool rgb = false;              // rgl-rgb: linear sRGB of each node's spectrum as a reflectance under D65
    int theta_i_count = 16;        // incidences, uniform over [0, theta_i_max_deg]
    double theta_i_max_deg = 88;   // beyond, readers use the last slice (the format's rule)
    int phi_i_count = 9;           // anisotropic models: incidence azimuths over [-pi, 0] (2-fold symmetry)
    int ndf_resolution = 128;      // NDF, sigma and VNDF: theta_m (u) nodes; phi_m nodes for VNDF and anisotropic NDF
    int sample_resolution = 64;    // luminance and spectral tables: nodes per side of the sample square
    double lambda_min_nm = 360, lambda_max_nm = 1000, lambda_step_nm = 3.2;  // spectral files
    double reference_lambda_nm = 550;  // the NDF's wavelength
    int threads = 0;               // 0: all hardware threads
};

// Throws Error on an option out of range (each named as the CLI spells it) or a model the material cannot evaluate
// over the wavelengths (its own message).
RglData export_rgl(const Bsdf& model, const RglExportOptions& options, const std::string& description);

// The coherent specular reflectance the file leaves out, delta_reflectance(wi, lambda), on a theta x lambda grid
// (rows theta_deg, columns lambda_nm): what a separate smooth conductor component must carry.
struct DeltaTable {
    std::vector<double> theta_deg, lambda_nm;
    std::vector<double> reflectance;  // theta-major
};
DeltaTable delta_table(const Bsdf& model, const std::vector<double>& theta_deg, const std::vector<double>& lambda_nm);

}  // namespace surfscatter::bsdf
