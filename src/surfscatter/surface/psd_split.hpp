#pragma once
// Macro/micro split of a PSD at zeta_c = k/N (THEORY.md 3.2): macro = low-pass part (slopes -> an NDF),
// micro = high-pass part P (1 - |H|^2) (diffraction lobe). Filters: sharp (|H|^2 = [zeta <= zeta_c]) or the
// ISO 16610 Gaussian with cutoff wavelength 2 pi / zeta_c (|H|^2 = 2^(-2 (zeta/zeta_c)^2)).
#include <memory>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

enum class LowPassFilter { sharp, iso_gaussian };

// zeta_c = 2 pi / (N lambda) in rad/um (lambda in nm).
double cutoff_frequency(double lambda_nm, double n_wavelengths);
// Low-pass power transfer |H(zeta)|^2 in [0, 1].
double low_pass_transfer(LowPassFilter, double zeta, double zeta_c);

// Statistics of base P times the ISO Gaussian power transfer (low- or high-pass): a smooth PSD, so its ACV by FFTLog
// (NumericalRadialStatistics) is accurate. The sharp filter's parts are SharpCutStatistics (sharp_cut.hpp).
class GaussianFilteredStatistics final : public NumericalRadialStatistics {
public:
    GaussianFilteredStatistics(std::shared_ptr<const RadialStatistics> base, double zeta_c, bool high_pass);

private:
    double psd_raw(double zeta) const override;
    std::shared_ptr<const RadialStatistics> base_;
    double zeta_c_;
    bool high_pass_;
};

struct PsdSplit {
    double zeta_c = 0;              // rad/um
    double sigma2_macro = 0;        // um^2
    double sigma2_micro = 0;        // um^2 (sigma2_macro + sigma2_micro = sigma_h^2)
    double slope2_macro = 0;        // <|grad h_LP|^2>
    // High-pass statistics (SharpCutStatistics for the sharp filter); null when the sharp cut leaves less than
    // kMinCutFraction of the variance above zeta_c (a map whose band ends below it: no micro roughness resolved).
    std::shared_ptr<const RadialStatistics> micro;
};

PsdSplit split_psd(std::shared_ptr<const RadialStatistics> base, double zeta_c, LowPassFilter);

// The sharp split of elliptical statistics (docs/MODELS.md "Two-scale on elliptical statistics"): the cut is the
// ellipse |(zeta_u, s zeta_v)| = R, R = zeta_c min(1, s) (s = LV / LU), the largest ellipse of the surface's own shape
// inside the circle |zeta| = zeta_c: the low-pass part holds only frequencies the wavelength does not resolve, and
// both parts stay stretches of radial statistics (the sharp cut of the radial one at R), so every self-convolution
// order of the micro part is the stretched isotropic one (elliptical_statistics.hpp). Per lay axis (THEORY 7.1)
// <h_u^2> = M / 2 and <h_v^2> = M / (2 s^2), M the radial mean-square slope below R; <h_u h_v> = 0. From the radial
// statistics' closed forms (CDF, cut slope): within 1e-12 of a 2-D quadrature of the elliptical KC PSD
// (TwoScaleElliptical.SplitMatchesTwoDimensionalQuadrature, tests/bsdf/test_two_scale_elliptical.cpp).
struct EllipticalPsdSplit {
    double cut_stretched = 0;       // R (rad/um) in the stretched plane
    double sigma2_macro = 0;        // um^2
    double sigma2_micro = 0;        // um^2
    Vec2 slope_variances_lay;       // <h_u^2>, <h_v^2> of the low-pass part
    std::shared_ptr<const EllipticalStatistics> micro;  // the high-pass part: SharpCutStatistics at R, stretched by s
};

EllipticalPsdSplit split_elliptical_psd(const EllipticalStatistics& stats, double zeta_c);

}  // namespace surfscatter::surface
