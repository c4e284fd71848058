#pragma once
// Rigorous 2-D scattering of a Thorsos-tapered beam by a 1-D profile z = h(x) (docs/REFERENCE.md): boundary integral
// equations discretised by a Nystrom rule whose weights next to the logarithmic singularity are corrected to
// seventh order (Navot's zeta-function correction of the trapezoid rule), solved by dense LU.
// Geometry: light in the x-z plane arriving from negative x, so that theta_o = +theta_i is specular; the beam is
// centred at x = 0 with its taper width g along x. Time dependence exp(-i omega t).
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

#include "surfscatter/material/conductor.hpp"
#include "surfscatter/reference/option_names.hpp"
#include "surfscatter/reference/profile.hpp"

namespace surfscatter::reference {

enum class Polarisation { s, p };  // s (TE): E along y; p (TM): H along y

// How the boundary system is solved (docs/REFERENCE.md, "Solve"): dense LU; GMRES with an FFT far part,
// preconditioned by the flat surface's operator (a circulant, by FFT) or for a perfect conductor in p by a banded
// near-field LU (O(N log N) per product); or automatic: iterative from kIterativeFromUnknowns
// unknowns, dense below and wherever the iterative route declines (a height range its far series cannot span, or
// no convergence).
enum class Exact1dSolver { automatic, dense, iterative };
inline constexpr std::size_t kIterativeFromUnknowns = 500;

struct Exact1dOptions {
    double lambda_nm = 0.0;
    double theta_i_rad = 0.0;          // in [0, pi/2)
    Polarisation polarisation = Polarisation::s;
    double beam_width_um = 0.0;        // Thorsos taper g
    double points_per_wavelength = 10; // solver nodes per wavelength along x, >= 4 (the profile is splined onto them)
    // A metal's interior kernels are kept within this many decay lengths 1/Im(k N) of each node (their size there is
    // exp(-interior_reach) of the nearest ones): 10..100.
    double interior_reach = 30;
    Exact1dSolver solver = Exact1dSolver::automatic;
    OptionNames option_names;
};

// The scattered far field on the grid theta_o = -90, -89.9, ..., 90 deg: amplitude[j] with |amplitude|^2 the
// scattered power per radian over the incident power (so a perfect conductor's integrates to 1).
struct FarField {
    std::vector<double> theta_o_rad;
    std::vector<std::complex<double>> amplitude;
    std::vector<double> intensity_per_rad() const;
};

inline constexpr int kFarFieldSteps = 1800;  // 0.1 deg

// Thorsos (1988) incident power through a horizontal line:
// sqrt(pi/2) g cos(theta_i) [1 - (1 + 2 tan^2 theta_i) / (2 k^2 g^2 cos^2 theta_i)], to O((k g cos)^-4).
double thorsos_incident_power(double k_per_um, double theta_i_rad, double beam_width_um);
// The normalisation of FarField: the power the beam's propagating plane waves carry down through z = 0,
// (1/2pi) int_{|K|<k} sqrt(1 - K^2/k^2) |A(K)|^2 dK with A(K) = int psi_inc(x, 0) e^{-iKx} dx (trapezoid rules, to
// ~1e-10), so that a flat perfect conductor reflects exactly 1. Thorsos' closed form differs by ~1e-4 at
// (1 + 2 tan^2) / (2 (k g cos)^2) = 5e-3.
double incident_power(double k_per_um, double theta_i_rad, double beam_width_um);
// The tapered incident field at (x, z), Thorsos eq. (19): exp(i k (x sin - z cos)(1 + w)) exp(-(x + z tan)^2/g^2),
// w = (2 (x + z tan)^2 / g^2 - 1) / (k g cos)^2.
std::complex<double> thorsos_beam(double k_per_um, double theta_i_rad, double beam_width_um, double x_um, double z_um);

// Profile ends at least this many beam widths from x = 0: Thorsos' L = 4 g (docs/REFERENCE.md: the truncation error
// it leaves; validity estimates it per case and refuses where it exceeds the tolerance).
inline constexpr double kProfileBeamMargin = 2.0;

// Solver nodes of one profile (the profile splined at points_per_wavelength per wavelength): counted before anything
// is allocated, a profile too long or too coarse for the wavelength is refused (docs/RELIABILITY.md).
inline constexpr double kMaxExact1dNodes = 1e7;

// What to do when the node count or the memory is too large, naming the caller's options with their values: "use
// fewer --points-per-wavelength (now 10), a shorter --length-um (now 1e+05 um) or a longer --wavelength (now 550 nm)"
// and, for `concurrent` > 1 solves at once, "or fewer --threads (now 8)".
std::string exact_1d_remedy(const Exact1dOptions& options, double length_um, std::size_t concurrent = 1);

// Throws Error naming the value (and options.option_names' option) for a bad wavelength, angle, beam width or
// sampling, a refractive index of 0 (n = k = 0) at the wavelength, a profile that does not hold the beam (its ends
// within 2 g of x = 0), or one that needs more than kMaxExact1dNodes nodes (with exact_1d_remedy).
FarField solve_exact_1d(const Profile& profile, const material::Conductor& conductor, const Exact1dOptions& options);

// The bytes one solve holds at its peak (docs/REFERENCE.md, "Memory"): every buffer that scales with the node count
// (the nodes, the route's matrices, the far series' spectra and workspace, GMRES's Krylov basis at its full restart
// length, the far field's arrays), planned as the solve plans its route. An upper bound: 1.0-2.5x the measured peak
// (tests/reference/test_exact_1d_memory.cpp). solve_exact_1d checks it against the available memory before it
// allocates; this builds the nodes (O(N)) to plan the route.
double exact_1d_solve_bytes(const Profile& profile, const material::Conductor& conductor, const Exact1dOptions& options);
// Throws Error (one line with exact_1d_remedy) when `concurrent_solves` such solves exceed the memory available now.
void require_exact_1d_memory(const Profile& profile, const material::Conductor& conductor,
                             const Exact1dOptions& options, std::size_t concurrent_solves);

}  // namespace surfscatter::reference
