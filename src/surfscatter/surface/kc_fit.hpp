#pragma once
// Fitting a K-correlation (KC) PSD, P(zeta) = sigma_h^2 P-hat(zeta; L_c, gamma) (THEORY.md 2.1), to a measured
// height map.
//
// Estimator: weighted least squares in log space over the radial rings of the Hann-windowed periodogram
// (psd_estimate.hpp) inside a band [zeta_min, zeta_max]:
//     minimise sum_i nu_i (ln Pbar_i - b_i - ln sigma^2 - ln P-hat(zeta_i; L, gamma))^2,
// nu_i = effective independent samples of ring i (the inverse variance of ln Pbar_i), b_i = psi(nu_i) - ln nu_i
// ~ -1/(2 nu_i) - 1/(12 nu_i^2) the mean of the log of a mean of nu exponentials (without it the low rings, where
// nu ~ 5-20, would read 2-10 % low and bias L_c). ln sigma^2 enters linearly and is solved in closed form for
// each (L, gamma); (ln L, ln(gamma - 1)) are found by a coarse grid search and then Eigen's Levenberg-Marquardt.
//
// Why the fitted sigma_h and not the map's rms: a patch of side W contains no wavelength longer than W, and tilt
// removal takes out part of the longest ones, and nothing beyond the Nyquist frequency is sampled; the rms of
// the patch is the PSD integrated over the sampled band only. The fit instead estimates the parameter of the
// process, which extrapolates the model below zeta_min and above zeta_max. Both are reported (SurfaceFit).
//
// The band: rings below min_ring are smeared by the Hann window's main lobe (+-2 rings) and by tilt removal;
// above max_nyquist_fraction * pi/dx real instruments lose resolution and aliasing folds the tail back (for a
// zeta^-(gamma+1) tail, at half Nyquist the folded power is ~3^-(gamma+1), 1 % for gamma = 3). The data resolve
// L_c only if the knee zeta ~ 1/L_c lies well inside the band: a fit that runs to the bounds of the search is
// reported as an Error rather than returned.
#include <cstddef>
#include <string>

#include "surfscatter/surface/elliptical_fit.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/surface/height_map_acv.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

struct KcFitOptions {
    std::size_t min_ring = 4;           // first ring used (1 = the lowest non-zero frequency)
    double max_nyquist_fraction = 0.5;  // zeta_max = this * pi / max(dx, dy), in (0, 1]
    heightmap::Form form = heightmap::Form::plane;            // removed before everything (fit_surface)
    // The rings are a profile's 1-D PSD (profile_statistics.hpp): fitted with the KC's profile PSD
    // (KCorrelation::profile_psd_unit), so that sigma_h, L_c and gamma are the isotropic surface's.
    bool profile = false;
};

struct KcFit {
    double sigma_h_um = 0.0;
    double corr_length_um = 0.0;
    double gamma = 0.0;
    double zeta_min = 0.0, zeta_max = 0.0;  // band used, rad/um
    std::size_t rings = 0;                  // rings in the band
    double log_residual_rms = 0.0;          // weighted rms of ln(data / model) (statistical floor ~ 1/sqrt(nu))
    double statistical_floor = 0.0;         // what log_residual_rms is for a KC surface: sqrt(rings / sum nu)
    // Empty when the fit is resolved; otherwise why not (the band searched and where the best attempt ended),
    // and the parameters above are that best attempt, inside the searched box.
    std::string failure;
};

// The search box of gamma - 1 (both KC fits, elliptical_fit.hpp); a fit that ends on its boundary did not resolve it.
inline constexpr double kKcGammaMinusOneMin = 0.02, kKcGammaMinusOneMax = 14.0;

// "lower" or "upper" when `value` lies within 2 % of the range [lo, hi] of that end (a search that ended there did
// not resolve the parameter), else nullptr.
const char* search_box_end(double value, double lo, double hi);

// A fit is poor when its misfit exceeds this many times its statistical floor.
inline constexpr double kPoorFitFactor = 2.0;

// Fits KC to the rings of `radial` (see above). Throws Error if the band holds fewer than 8 rings; a correlation
// length or gamma that the band does not resolve sets `failure` (require_resolved() throws it).
KcFit fit_kc(const RadialPsd& radial, double nyquist_zeta, const KcFitOptions& options = {});
void require_resolved(const KcFit& fit);

// Everything `surfscatter surface fit` reports about a height map.
struct SurfaceFit {
    KcFit kc;
    double rms_height_um = 0.0;        // rms of the form-removed map over its valid points (band-limited, see above)
    double rms_slope = 0.0;            // central differences on the form-removed map (height_map_slope.hpp)
    double rms_slope_from_psd = 0.0;   // sqrt(sum zeta^2 P dzeta^2) of the windowed periodogram
    Psd2d psd;                         // the 2-D PSD of the form-removed map
    RadialPsd radial;                  // its rings: the data that were fitted
    AcvMeasures acv;                   // Str and the lay direction (height_map_acv.hpp): anisotropy the fit ignores
    // The elliptical KC fit (elliptical_fit.hpp) and the periodogram it fitted: MapStatistics' window rule
    // (is_periodic(): rectangular for a periodic map), so not always `psd`.
    EllipticalKcFit elliptical;
    Psd2d spectrum;
    // The fitted KC's rms summed over the periodogram's lattice (what it says the map should hold), the
    // periodogram's (what the map holds, its windowed variance), and the latter's relative standard error.
    double fit_lattice_rms_um = 0.0, map_lattice_rms_um = 0.0, lattice_rms_error = 0.0;
};

// The fit's rms on the map's lattice may differ from the map's by this fraction, or 3 standard errors if more, before
// lattice_rms_check() objects.
inline constexpr double kLatticeRmsTolerance = 0.1;
// Beyond this factor either way the fit does not describe the map at all (`surface fit` and psd file refuse it).
inline constexpr double kLatticeRmsRefusal = 2.0;

// Empty when the fitted KC holds the map's variance on the map's own lattice within kLatticeRmsTolerance (or 3
// standard errors), otherwise why not, in one line.
std::string lattice_rms_check(const SurfaceFit& fit);

// Removes options.form once, then PSD, both fits, rms and slopes over the valid points. Error if fewer than
// kMinFitValidFraction of the points are valid.
SurfaceFit fit_surface(const heightmap::HeightMap& map, const KcFitOptions& options = {});

// Nyquist angular frequency pi / max(dx, dy) of a map (rad/um).
double nyquist_zeta(const heightmap::HeightMap& map);

}  // namespace surfscatter::surface
