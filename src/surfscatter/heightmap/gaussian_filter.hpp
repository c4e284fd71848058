#pragma once
// ISO 16610-61 areal Gaussian filters: the S-filter removes periods shorter than lambda_s, the L-filter those longer
// than lambda_c; weighting function s(r) = exp(-pi (r / (alpha lc))^2) / (alpha lc)^2, alpha = sqrt(ln 2 / pi), which
// transmits exp(-pi (alpha lc / lambda)^2) of a sinusoid of period lambda (50 % at lc). Over the valid points as a
// normalised convolution (at the edges, ISO 16610-28's zero-order end-effect correction: a constant is kept, a slope
// a biased by a alpha lc / pi), by FFT of the map zero-padded by the kernel's reach. Transmission, edges, masks,
// sampling limits, why not Gwyddion's filter, and the default lambda_c: docs/HEIGHTMAPS.md "Areal Gaussian filters
// (ISO 16610-61)".
#include <string>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// Smallest nesting index, in the coarser pixel spacing (ISO 25178-3's ratio of lambda_s to the sampling distance);
// there the sampled s transmits 12 % more than the closed form at lambda = lc (0.4 % at 4, 3e-5 at 5 spacings).
inline constexpr double kMinNestingPixels = 3.0;

// The mean surface at nesting index lc (um): the waviness for lambda_c, the map without its shortest periods for
// lambda_s. Same grid and mask. Error unless lc is finite and at least kMinNestingPixels spacings along both axes.
HeightMap gaussian_lowpass(const HeightMap& map, double nesting_index_um);

struct Filtered {
    HeightMap kept;
    HeightMap removed;
};
// S-filter: kept = the lowpass at lambda_s, removed = the map minus it (the periods shorter than lambda_s).
Filtered s_filter(const HeightMap& map, double lambda_s_um);
// L-filter: kept = the map minus the lowpass at lambda_c (roughness), removed = that lowpass (waviness).
Filtered l_filter(const HeightMap& map, double lambda_c_um);

// The relative standard error of sigma the default L-filter must reach (the models warn above it).
inline constexpr double kLambdaCSigmaError = 0.10;

// Relative standard error of the rms of a random surface with this map's spectrum, from the rings of its 2-D
// periodogram (Hann window): sqrt(sum_k M_k^2 / nu_k) / (2 sum_k M_k), M_k the variance in ring k, nu_k = N_k /
// (2 (35/18)^2) independent samples for its N_k lattice points (the 2-D Hann window correlates each bin with its
// 5 x 5 neighbours, sum rho^2 = (35/18)^2; measured against the scatter over 48 synthesised maps, within 10 %).
// With lambda_c > 0 each ring's variance is first multiplied by the L-filter's power transmission
// (1 - exp(-pi (alpha lambda_c zeta_k / 2 pi)^2))^2. Error unless lambda_c is finite and >= 0.
double sigma_relative_error(const HeightMap& map, double lambda_c_um = 0.0);

// The default L-filter nesting index for a form-removed map (um), 0 for none: 0 when the map resolves its spectrum
// (sigma_relative_error() <= kLambdaCSigmaError), otherwise the longest nesting index of the 1-2-5 series at which
// the filtered map's sigma has that standard error (the 1-2-5 series of ISO 25178-3 Table 1: 1, 2, 5, 10, 20 ..
// um), and 0 if none from kMinNestingPixels spacings to the map's longer side does. `reason` (if given) gets one line
// saying which and why.
// `shortest_um` bounds the nesting indices tried from below (prepare() passes kShortestWavinessUm).
double default_lambda_c(const HeightMap& form_removed_map, std::string* reason, double shortest_um = 0.0);

}  // namespace surfscatter::heightmap
