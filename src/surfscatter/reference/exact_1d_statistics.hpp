#pragma once
// The exact 1-D solution averaged over random profiles (docs/REFERENCE.md, "Statistical mode"): realizations solved
// in parallel, the mean far field split into its coherent part |<a>|^2 and its incoherent part <|a - <a>|^2>, each
// with its Monte Carlo standard error, both estimated with a control variate: the same profile's Kirchhoff far field
// under the beam's footprint, whose ensemble mean and variance are known in closed form for the synthesised
// (Gaussian, periodic) profiles.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "surfscatter/material/conductor.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/profile.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::reference {

struct StatisticalResult {
    std::vector<double> theta_o_rad;
    // Per radian over the incident power. intensity: the plain mean <|a|^2> (each realization conserves energy, so
    // its integral carries no Monte Carlo error); coherent and incoherent: the controlled estimates, whose sum
    // differs from intensity by the control's correction (within their standard errors).
    std::vector<double> intensity, coherent, incoherent;
    std::vector<double> coherent_stderr, incoherent_stderr;
    // The incoherent part without the control (the sample variance of a) and its standard error: the variance
    // reduction is (incoherent_plain_stderr / incoherent_stderr)^2.
    std::vector<double> incoherent_plain, incoherent_plain_stderr;
    // 2 / (k g cos theta_i): the half-width at 1/e^2 of the beam's angular power spectrum (its incident directions),
    // the angular resolution of the reference. Within it of specular the coherent beam dominates and the incoherent
    // part is the plane-wave lobe blurred by the beam; a comparison with plane-wave models leaves those directions out.
    double beam_half_width_rad = 0.0;
    std::size_t realizations = 0;  // completed (fewer than asked if interrupted)
};

// The fewest realizations whose estimates use the control variate (docs/REFERENCE.md): fewer leave the controlled
// standard errors too small: between two independent runs (KC sigma 0.1 um, L 1 um, 1000 nm) the rms of the
// difference over its standard error was 1.5, 1.4, 1.15 and 1.03 at 12, 16, 24 and 48 realizations (the influence
// values are squares, heavy-tailed, and the fitted coefficient follows them).
inline constexpr std::size_t kMinControlledRealizations = 24;

struct StatisticalOptions {
    double length_um = 0.0;        // profile length, centred on x = 0
    std::size_t realizations = 0;  // >= 2; with `more`, the most that are run
    std::uint64_t seed = 0;        // realization r uses seed + r
    int threads = 0;               // 0: all hardware threads
    bool progress = false;         // progress bar with ETA on stderr
    // Precision on request: when set, realizations run in rounds, the first of `first_round` (>= 2); after each,
    // more(result so far) says how many more are wanted (0: enough), up to `realizations` in all.
    std::function<std::size_t(const StatisticalResult&)> more;
    std::size_t first_round = kMinControlledRealizations;  // a smaller one is judged by the plain estimates
};

// The samples of a profile of length_um at lambda / points_per_wavelength, checked without allocating: Error (naming
// options.option_names' options, with exact_1d_remedy) for a length or wavelength <= 0 or more than kMaxExact1dNodes.
std::size_t profile_samples(const Exact1dOptions& options, double length_um);

// The flat profile (every height 0) sampled at lambda / points_per_wavelength over length_um, centred on x = 0: the
// grid of every random profile. Throws Error for a length or wavelength <= 0 or more than kMaxExact1dNodes samples.
Profile flat_profile(const Exact1dOptions& options, double length_um);

// The random profile of realization `index`: a cut through an isotropic surface with `statistics`
// (surface::synthesize_profile with its zero-frequency line), sampled at lambda / points_per_wavelength over
// length_um, centred on x = 0.
Profile random_profile(const surface::RadialStatistics& statistics, const Exact1dOptions& options, double length_um,
                       std::uint64_t seed);

// Stops early (keeping the realizations completed) when interrupt_requested(); throws Error for bad options.
StatisticalResult solve_exact_1d_statistics(const surface::RadialStatistics& statistics,
                                            const material::Conductor& conductor, const Exact1dOptions& options,
                                            const StatisticalOptions& statistical);

}  // namespace surfscatter::reference
