#pragma once
// The Kirchhoff (physical-optics, tangent-plane) BRDF of a height map itself (docs/REFERENCE.md, "reference
// kirchhoff"; THEORY.md 7.4, Yan et al. 2018): no stationarity, Gaussian heights or PSD fit is assumed.
//
// Formulation (scalar Kirchhoff with the facet obliquity eliminated by the stationary-phase identity, Beckmann's
// form): with q = k (i + o) (both directions away from the surface, k = 2 pi / lambda) and a window W over a square
// sub-area,
//   I(q)   = sum_pixels W(x) exp(i (q_xy . x + q_z h(x))) dx dy,
//   f_r    = F(theta_d) |q|^4 / (16 pi^2 q_z^2 cos(theta_i) cos(theta_o)) |I(q)|^2 / A_W,   A_W = sum W^2 dx dy,
// averaged over the sub-areas that tile the map. F is the unpolarised (s and p averaged) Fresnel reflectance at the
// half-vector angle, cos(theta_d) = |q| / 2k (the local facet angle where the phase is stationary). This f_r tends
// to the geometric-optics F p(slope) / (4 cos i cos o cos^4 theta_h) at large roughness and to the mirror with
// reflectance F(theta_i) on a flat map.
//
// Discretisation: the window is a separable Hann window, W = sin^2(pi (j + 1/2) / n) per axis, so the directions are
// the DFT lattice of a sub-area of n_x x n_y pixels: o_xy = q_xy / k - i_xy with q = 2 pi (m_x / (n_x dx),
// m_y / (n_y dy)), |m| < n / 2, lattice steps lambda / (n dx) in direction cosines (the angular resolution; the
// window's main lobe is 2 steps wide each side), up to the Nyquist |q_x| < pi / dx (the largest scattering angle the
// pixel resolves). q_z = k (cos i + cos o) varies with the direction, so the directions are grouped into equal bands
// of q_z of half-width delta <= 4 / r (r = max |h - mean| over the sub-area; the count that needs the fewest FFTs)
// and, within a band centred at q_c,
//   exp(i q_z u) = exp(i q_c u) sum_{n=0..N} (i (q_z - q_c) u)^n / n!   (u = h - mean),
// one FFT per term, N chosen so that the remainder e^(delta r) (delta r)^(N+1) / (N+1)! <= 1e-10: every direction's
// amplitude is its exact DFT to 1e-10 of sum W dx dy (the flat mirror's amplitude), measured against a direct sum in
// `KirchhoffMap.BandExpansionMatchesDirectSum`.
//
// Sub-areas: the largest whole number of side `subarea_um` (rounded to pixels) per axis, centred on the map, without
// overlap (so the standard errors treat them as independent); sub-areas holding an invalid point are skipped.
// The coherent part is the same expression with the sub-areas' mean amplitude: it carries the specular peak,
// spread over the window's lobe, and is biased upwards by the incoherent part / M for M sub-areas.
//
// Refused (Error): fewer than 2 usable sub-areas, sub-areas under 16 pixels a side, and sampling too coarse for the
// wavelength: more than 1e-3 of the neighbouring pixel pairs whose phase q_z,max |h_1 - h_2| exceeds pi (there the
// integrand's local frequency passes the Nyquist limit and that energy is aliased into other directions).
// Warned (KirchhoffResult::warnings): directions the pixel cannot resolve, skipped sub-areas, a diffuse lobe
// narrower than 3 lattice steps (sub-areas too small to resolve it), any aliased pair at all.
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "surfscatter/material/conductor.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/reference/option_names.hpp"

namespace surfscatter::reference {

struct KirchhoffOptions {
    double lambda_nm = 0.0;
    double theta_i_rad = 0.0;  // [0, pi/2)
    double phi_i_rad = 0.0;    // in the map's frame: x towards phi = 0, y towards phi = 90 deg
    double subarea_um = 0.0;   // side of the square sub-areas (rounded to whole pixels per axis)
    double max_theta_o_rad = 85.0 * 3.14159265358979323846 / 180.0;  // directions kept: theta_o <= this, (0, pi/2)
    int threads = 0;           // sub-areas evaluated at once, 0 = all cores
    bool progress = false;     // progress bar with ETA on stderr
    OptionNames option_names;  // as the caller spells them (wavelength, sub-area side, threads)
};

// Throws Error naming options.option_names.subarea unless the sub-area side holds at least kMinSubareaPixels pixels
// of `map` and at most the map along each axis: validity checks its maps before its progress starts.
void require_kirchhoff_subarea(const heightmap::HeightMap& map, const KirchhoffOptions& options);

struct KirchhoffResult {
    // One entry per lattice direction kept, row by row (m_y, then m_x increasing).
    std::vector<double> o_x, o_y;            // direction cosines of the outgoing direction
    std::vector<double> brdf;                // 1/sr, mean over the sub-areas, coherent part included
    std::vector<double> standard_error;      // 1/sr, of brdf over the sub-areas
    std::vector<double> coherent;            // 1/sr, the part from the sub-areas' mean amplitude
    double step_x = 0.0, step_y = 0.0;       // lattice steps in direction cosines (lambda / sub-area side)
    double albedo = 0.0;                     // sum brdf * step_x * step_y over the directions kept
    double albedo_standard_error = 0.0;      // over the sub-areas
    double coherent_albedo = 0.0;
    double aliased_fraction = 0.0;           // of neighbouring pixel pairs with a phase step above pi
    std::size_t subarea_nx = 0, subarea_ny = 0;  // pixels
    std::size_t subareas = 0;                // usable sub-areas
    std::size_t subareas_done = 0;           // evaluated (fewer when interrupted)
    std::size_t fft_count = 0;               // FFTs per sub-area (bands x terms), the most any sub-area took
    std::size_t band_count = 0;              // q_z bands, the most any sub-area took
    std::vector<std::string> warnings;       // one line each
    std::string lobe_unresolved;             // the warning when the diffuse lobe is under 3 lattice steps (rms)
};

// The map's heights are used as they are: remove the form first (heightmap::remove_form). Throws Error for bad
// options or a map that cannot be trusted at this wavelength (see above). Polls interrupt_requested() between
// sub-areas: an interrupted run returns the sub-areas done (standard errors need 2; with fewer they are 0 and
// `warnings` says so).
KirchhoffResult kirchhoff_brdf(const heightmap::HeightMap& map, const material::Conductor& conductor,
                               const KirchhoffOptions& options);

}  // namespace surfscatter::reference
