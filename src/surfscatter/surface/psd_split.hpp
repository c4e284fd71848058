#pragma once
// Macro/micro split of a PSD at zeta_c = k/N (THEORY.md 3.2): macro = low-pass part (slopes -> an NDF),
// micro = high-pass part P (1 - |H|^2) (diffraction lobe). Filters: sharp (|H|^2 = [zeta <= zeta_c]) or the
// ISO 16610 Gaussian with cutoff wavelength 2 pi / zeta_c (|H|^2 = 2^(-2 (zeta/zeta_c)^2)).
#include <memory>

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
    std::shared_ptr<const RadialStatistics> micro;  // high-pass statistics (SharpCutStatistics for the sharp filter)
};

PsdSplit split_psd(std::shared_ptr<const RadialStatistics> base, double zeta_c, LowPassFilter);

}  // namespace surfscatter::surface
