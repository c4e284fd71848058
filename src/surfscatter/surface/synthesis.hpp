#pragma once
// Random Gaussian surfaces with a prescribed isotropic PSD, by spectral synthesis.
//
// White Gaussian noise n (unit variance per pixel) is transformed, multiplied by A_k = sqrt(N P(|zeta_k|) dzeta_x
// dzeta_y) and transformed back with 1/N. The result is a periodic, stationary Gaussian field on the nx x ny grid
// whose covariance is the lattice Fourier series of P: Var h = sum_k P(zeta_k) dzeta^2 over the grid's frequencies
// up to Nyquist (the k = 0 term is set to zero, so the map has zero mean). This is slightly less than the model's
// sigma_h^2: the PSD mass beyond Nyquist and inside the first frequency cell is absent (for KC with L = 10 dx and
// gamma = 2, 3 % of the variance lies beyond Nyquist). Filtering white noise (instead of drawing complex
// amplitudes) gives the Hermitian symmetry and the Nyquist rows for free.
//
// Deterministic: the noise comes from std::mt19937_64 (its output sequence is fixed by the C++ standard) through
// a Box-Muller transform written here, because std::normal_distribution's algorithm is implementation-defined;
// so the same seed gives a bit-identical surface with any standard library.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

struct SynthesisGrid {
    std::size_t nx = 0, ny = 0;  // samples, >= kMinHeightMapSize
    double spacing_um = 0.0;     // pixel spacing (square pixels)
};

// A surface with the PSD statistics.psd(zeta) (um^4, zeta in rad/um, e.g. KCorrelation or GaussianAcv).
heightmap::HeightMap synthesize_surface(const RadialStatistics& statistics, const SynthesisGrid& grid, std::uint64_t seed);
// The same with the 2-D PSD sigma_h^2 statistics.psd_unit(zeta) of an anisotropic surface (x along the map's rows);
// with LV = LU bit-identical to the radial one's for the same seed.
heightmap::HeightMap synthesize_surface(const EllipticalStatistics& statistics, const SynthesisGrid& grid, std::uint64_t seed);

// The PSD of a straight cut z = h(x, y0) through an isotropic surface: P1(zeta_x) = int P(sqrt(zeta_x^2 + zeta_y^2))
// dzeta_y in um^3, so that int P1 dzeta_x = sigma_h^2 and the cut's ACV is C(|x|) (THEORY.md 2.1 has KC's closed
// form). By adaptive quadrature to 1e-10 relative.
double profile_psd(const RadialStatistics& statistics, double zeta_x);

// Whether a synthesised profile keeps the zero-frequency line: `zero` sets it to 0 (each profile has zero mean);
// `random` draws it like every other line, variance P1(0) dzeta, from the same noise. A finite window (a beam) sees
// a cut through the surface whose local mean varies: without the line, the scattering a window collects from the
// frequencies within its own spectral width of zero is missing (exact-1d's incoherent part near specular, issue 34).
enum class ProfileMean { zero, random };

// A random profile of n samples (>= 4) spaced spacing_um apart with the 1-D PSD profile_psd: the same spectral
// synthesis and noise as synthesize_surface in one dimension (periodic over n spacing, variance sum_k P1(zeta_k)
// dzeta over the lines k up to Nyquist, k = 0 included with ProfileMean::random). The lines' amplitudes are
// independent Gaussians with E|c_k|^2 = P1(|zeta_k|) dzeta, h_j = sum_k c_k exp(2 pi i k j / n).
std::vector<double> synthesize_profile(const RadialStatistics& statistics, std::size_t n, double spacing_um,
                                       std::uint64_t seed, ProfileMean mean = ProfileMean::zero);

}  // namespace surfscatter::surface
