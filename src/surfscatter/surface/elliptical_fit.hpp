#pragma once
// Fitting an elliptical K-correlation PSD (elliptical_statistics.hpp, issue 24's convention) to a height map's 2-D
// periodogram:
//     P(zeta) = sigma^2 (gamma - 1) LU LV / (2 pi) (1 + LU^2 zeta_u^2 + LV^2 zeta_v^2)^(-(gamma+1)/2),
//     zeta_u = zeta_x cos A + zeta_y sin A, zeta_v = -zeta_x sin A + zeta_y cos A,
// i.e. sigma^2 times EllipticalStatistics(KCorrelation(1, LU, gamma), LV, A).psd_unit(zeta). x is the map's column
// direction, y its row direction (height_map.hpp), A from +x towards +y.
//
// Data: the 2-D periodogram (psd_estimate.hpp) in the band of the isotropic fit (kc_fit.hpp: rings min_ring to
// max_nyquist_fraction of Nyquist), with MapStatistics' window rule (a periodic map the rectangular window, any other
// the Hann window; masked maps the masked correlogram). Each periodogram bin scatters by ~100 % (an exponential
// variable), so the bins are pooled into polar cells: every ring is cut into sectors over [0, 180) deg (the
// periodogram is point-symmetric) holding about kEllipticalCellPoints full-plane points each, i.e. nu ~ 8 independent
// samples with the Hann window and 16 with the rectangular one (effective_samples()). The estimator is the isotropic
// fit's, per cell instead of per ring: minimise sum_c nu_c (ln Pbar_c - b_c - ln sigma^2 - ln Phat_c)^2, Phat_c the
// model's mean over the cell's bins (the exact expectation of the cell mean, window leakage aside), b_c the log bias of
// a mean of nu exponentials, ln sigma^2 solved in closed form. nu_c is effective_samples() of the cell's points times
// (sum mu)^2 / (n sum mu^2) under the fitted model (a mean of exponentials with unequal means mu_k scatters more: wide
// low-ring sectors of a strongly anisotropic PSD), set after a first fit with flat cells, then refitted. Statistical
// floor: sqrt(cells / sum nu) (what the weighted rms of ln(data / model) is for an elliptical KC surface: measured
// 0.98-1.05 times it on the tests' 512^2 maps and 0.91-1.10 on five 128^2 maps with LV / LU = 0.25, where flat cell
// weights read 1.1-1.4), as for the isotropic fit.
//
// Parameters: (ln sqrt(LU LV), e1, e2, ln(gamma - 1)) with (e1, e2) = ln(LU / LV) (cos 2A, sin 2A): the quadratic form
// LU^2 zeta_u^2 + LV^2 zeta_v^2 is exp of a symmetric matrix linear in them, smooth through isotropy (where A is
// undefined), so that LU >= LV and A in [0, 180) deg come out without folding. Start: the 2-D second-moment tensor of
// the periodogram over the band (its eigenvector of the smaller eigenvalue along u, the square root of the eigenvalue
// ratio LV / LU, as for the slope covariance of THEORY 7.1) with the isotropic fit's L and gamma, and the isotropic
// fit itself; then Levenberg-Marquardt. The search box is the isotropic fit's for each of LU and LV and for gamma; a fit
// ending at its edge sets `failure` (as KcFit does).
//
// Uncertainty: the covariance of the five parameters from the weighted Jacobian at the optimum, inflated by the
// reduced chi-square where the model misfits (> 1): standard errors of sigma, LU, LV, gamma and A. Anisotropy is
// significant when the Wald statistic of (e1, e2) against isotropy exceeds kAnisotropyChi2 (2 degrees of freedom,
// 1e-3 false-alarm probability for an isotropic KC surface). Accuracy on synthetic elliptical KC maps (512^2,
// LU = 8 um, gamma 2.5, LV / LU 0.5 and 0.2, A 0, 30, 90, 135 deg; tests/surface/test_elliptical_fit.cpp): every
// error within 2.0 standard errors (LU, LV 2.2-3.5 %, A 0.1-0.24 deg, gamma 0.025); measured worst 3.8 % on LU and LV,
// 0.24 deg on A, 0.05 on gamma (the test holds them to 6 %, 1 deg, 0.1). Isotropic maps (LV = LU): LV / LU
// 0.989-0.996 +- 0.005 (LU >= LV by construction biases it below 1 by about one standard error), not significant.
#include <cstddef>
#include <string>

#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/psd_estimate.hpp"

namespace surfscatter::surface {

struct KcFit;

// Full-plane periodogram points per polar cell (see above).
inline constexpr double kEllipticalCellPoints = 32.0;
// chi-square (2 dof) above which the anisotropy is significant: exp(-13.8 / 2) = 1e-3.
inline constexpr double kAnisotropyChi2 = 13.8;

struct EllipticalKcFit {
    double sigma_h_um = 0.0;
    double corr_length_u_um = 0.0;  // LU >= LV
    double corr_length_v_um = 0.0;
    double gamma = 0.0;
    double lay_angle_deg = 0.0;     // A in [0, 180)
    // Standard errors (see above); lay_angle_error_deg is meaningless (large) when the anisotropy is not significant.
    double sigma_h_error_um = 0.0, corr_length_u_error_um = 0.0, corr_length_v_error_um = 0.0, gamma_error = 0.0;
    double lay_angle_error_deg = 0.0;
    double axis_ratio_error = 0.0;  // of LV / LU
    double anisotropy_chi2 = 0.0;   // Wald statistic of (e1, e2) against isotropy
    Window window = Window::hann;   // of the periodogram fitted
    double zeta_min = 0.0, zeta_max = 0.0;  // band, rad/um (the isotropic fit's)
    std::size_t cells = 0;          // polar cells fitted
    std::size_t skipped_cells = 0;  // cells whose mean is not positive (masked estimates)
    double log_residual_rms = 0.0;  // weighted rms of ln(data / model) over the cells
    double statistical_floor = 0.0; // sqrt(cells / sum nu)
    // Empty when resolved; otherwise why not, and the values above are the best attempt (held within e^0.5 of the
    // box's edge, as fit_kc holds its own).
    std::string failure;

    bool anisotropic() const { return anisotropy_chi2 > kAnisotropyChi2; }
    double axis_ratio() const { return corr_length_v_um / corr_length_u_um; }
    // The fit as the models' statistics (KC of sigma, LU, gamma stretched to LV along v, lay angle A).
    EllipticalStatistics statistics() const;
};

// Fits the elliptical KC to `psd` in the band of `isotropic` (fit_kc on the same map), started from its L and gamma.
// An unresolved fit, or a band of fewer than 16 cells (then the isotropic fit is the best attempt), sets `failure`.
EllipticalKcFit fit_elliptical_kc(const Psd2d& psd, const KcFit& isotropic);
void require_resolved(const EllipticalKcFit& fit);

// The fitted PSD P(zeta) (um^4) on the lattice of `like` (its values replaced; window and grid kept): for pictures of
// data / model and for the fit's ring means (radial_average()).
Psd2d fitted_psd(const EllipticalKcFit& fit, const Psd2d& like);

}  // namespace surfscatter::surface
