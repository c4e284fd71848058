#pragma once
// PSD estimation from a height map, in the angular convention of THEORY.md section 0:
// C(r) = integral of P(zeta) e^{i zeta.r} d2zeta, so the integral of P over the zeta-plane is the height variance.
//
// Estimator (windowed periodogram): remove the least-squares form (heightmap/form.hpp; a plane by default),
// multiply by a separable window w(ix, iy) = w_x(ix) w_y(iy), FFT, and
//     P(zeta_k) = |FFT(w h)_k|^2 dx dy / (4 pi^2 sum_n w_n^2),
// which is the cyclic periodogram |H|^2 dx dy / N divided by 4 pi^2 (P_angular = PSD_f / 4 pi^2) with the window's
// power loss sum w^2 / N undone. Parseval then holds exactly: sum_k P(zeta_k) dzeta_x dzeta_y =
// sum_n (w_n h_n)^2 / sum_n w_n^2, the window-weighted variance of the form-removed map (windowed_variance()).
// The Hann window w(i) = sin^2(pi (i + 1/2) / n) tapers the map to zero at its borders, so that the jump between
// opposite edges of a non-periodic measurement does not leak power (as zeta^-2) into the high frequencies; its
// price is a main lobe of +-2 bins, so the lowest few radial bins are smeared (kc_fit.hpp skips them).
//
// Maps with invalid points (mask m = 0 there): fill-free masked correlogram, prewhitened (masked_periodogram();
// docs/HEIGHTMAPS.md has the derivation and the measured bias). The periodogram above is the DFT of the lag
// products sum_n (w h)_n (w h)_(n+t) / sum w^2, whose mean is C(t) L(t), L(t) = sum_n w_n w_(n+t) / sum w^2 the
// window's own autocorrelation. With a mask the lag products exist only between valid pairs; their
// window-weighted mean C^(t) = sum (w m h)_n (w m h)_(n+t) / sum (w m)_n (w m)_(n+t) is an unbiased estimate of
// C(t) for any mask, so DFT[C^(t) L(t)] dx dy / (4 pi^2) has the mean of the unmasked Hann periodogram: no fill
// values, no power lost to the invalid fraction, no white floor (a plain masked periodogram |FFT(w m h)|^2 has all
// three). The mask still leaks the map's variance into every frequency as scatter, which swamps a steep tail; so
// above ring kMaskedDirectRings the estimator is applied to the slopes between valid neighbours (PSD T P, far
// flatter) and divided by the window-smoothed transfer function K * T. Lags without a valid pair (only when the
// valid region is cut into pieces) contribute 0. Values can be negative where the PSD lies far below the scatter
// (the fit and the table skip rings and bins whose mean is not positive); Parseval holds only approximately.
// Cost: six zero-padded 2nx x 2ny FFTs instead of one nx x ny.
#include <cstddef>
#include <vector>

#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/form.hpp"

namespace surfscatter::surface {

enum class Window { rectangular, hann };

// Half-plane 2-D PSD (kx = 0 .. nx/2, all ky), values in um^4 (um^2 of height variance per (rad/um)^2).
struct Psd2d {
    std::size_t nx = 0, ny = 0;   // grid of the map it came from
    Window window = Window::hann;
    double dzeta_x = 0.0;         // 2 pi / (nx dx), rad/um
    double dzeta_y = 0.0;         // 2 pi / (ny dy)
    double valid_weight = 1.0;    // sum (w m)^2 / sum w^2: the window-weighted valid fraction (1 without a mask)
    std::vector<double> values;   // [ky * (nx/2 + 1) + kx]

    std::size_t half_nx() const { return nx / 2 + 1; }
    double zeta_x(std::size_t kx) const;  // rad/um, >= 0
    double zeta_y(std::size_t ky) const;  // rad/um, signed
    // How many points of the full zeta-plane the half-plane entry at column kx stands for (1 or 2).
    double multiplicity(std::size_t kx) const;
    // sum over the full plane of P dzeta_x dzeta_y (um^2).
    double integral() const;
};

// Removes the form, applies the window, and returns the periodogram described above (the masked correlogram if
// the map has invalid points).
Psd2d estimate_psd(const heightmap::HeightMap& map, Window window = Window::hann, heightmap::Form form = heightmap::Form::plane);

// Rings up to this one take the masked correlogram of the heights, the others that of the slopes (see above).
inline constexpr double kMaskedDirectRings = 8;

// The masked estimate of a map whose form is already removed (what estimate_psd() uses for a map with invalid
// points).
Psd2d masked_periodogram(const heightmap::HeightMap& flat, Window window = Window::hann);

// sum (w m h)^2 / sum (w m)^2 of the form-removed map: what Psd2d::integral() of estimate_psd() equals (without
// invalid points exactly; with them approximately).
double windowed_variance(const heightmap::HeightMap& map, Window window = Window::hann, heightmap::Form form = heightmap::Form::plane);

// Window value for sample i of n.
double window_value(Window window, std::size_t i, std::size_t n);

// Azimuthal average over rings of width dzeta = max(dzeta_x, dzeta_y) centred on multiples of dzeta, from the
// first ring (the DC ring 0 is dropped: it is what tilt removal and the window set) up to the smaller Nyquist
// frequency pi / max(dx, dy), so that every ring is complete.
struct RadialPsd {
    Window window = Window::hann; // of the periodogram it came from
    double valid_weight = 1.0;    // of the periodogram it came from
    double dzeta = 0.0;           // ring width, rad/um
    std::vector<double> zeta;     // mean |zeta| of the ring's points, rad/um
    std::vector<double> psd;      // mean P over the ring, um^4
    std::vector<double> count;    // number of full-plane points in the ring
};

RadialPsd radial_average(const Psd2d& psd);

// Periodogram values are exponentially distributed about the PSD, each with 2 degrees of freedom, and the window
// correlates neighbours: a ring mean over `count` full-plane points (half of them Hermitian mirrors) behaves like
// a mean of count / (2 f) independent exponentials, f = sum_j |R_j|^2 over the window's normalised spectral
// correlation R_j along the ring (rectangular: 1; Hann: 1 + 2 (2/3)^2 + 2 (1/6)^2 = 35/18, confirmed by the
// spread of ln(ring mean) over 100 synthetic surfaces). A masked estimate has fewer independent pairs: the count is
// scaled by the window-weighted valid fraction (`valid_weight`, see above). Used as the fit weight and for the
// log-bias correction.
double effective_samples(Window window, double count, double valid_weight = 1.0);

// rms slope sqrt(sum |zeta|^2 P dzeta^2) from a 2-D PSD (THEORY.md 4.1): the slope of the band-limited map,
// i.e. up to the Nyquist frequency of the grid. Error if a masked estimate's sum is not positive.
double rms_slope_from_psd(const Psd2d& psd);

}  // namespace surfscatter::surface
