#include "surfscatter/surface/psd_split.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/sharp_cut.hpp"

namespace surfscatter::surface {

double cutoff_frequency(double lambda_nm, double n_wavelengths) {
    require_positive(lambda_nm, "wavelength");
    require_positive(n_wavelengths, "cutoff in wavelengths");
    return 2.0 * kPi / (n_wavelengths * lambda_nm * 1e-3);
}

double low_pass_transfer(LowPassFilter filter, double zeta, double zeta_c) {
    if (filter == LowPassFilter::sharp) return zeta <= zeta_c ? 1.0 : 0.0;
    const double t = zeta / zeta_c;
    return std::exp2(-2.0 * t * t);
}

GaussianFilteredStatistics::GaussianFilteredStatistics(std::shared_ptr<const RadialStatistics> base, double zeta_c,
                                                       bool high_pass)
    : base_(std::move(base)), zeta_c_(zeta_c), high_pass_(high_pass) {
    require_positive(zeta_c, "cutoff frequency");
    const double l = base_->correlation_length();
    zeta_lo_ = std::min(1e-3 / l, 1e-3 * zeta_c);
    zeta_hi_ = std::max(1e3 / l, 1e3 * zeta_c);
    initialise(fmt::format("{}({},iso-gauss,zc={:.17g})", high_pass ? "highpass" : "lowpass", base_->cache_key(),
                           zeta_c));
}

double GaussianFilteredStatistics::psd_raw(double zeta) const {
    const double t = low_pass_transfer(LowPassFilter::iso_gaussian, zeta, zeta_c_);
    return base_->psd(zeta) * (high_pass_ ? 1.0 - t : t);
}

PsdSplit split_psd(std::shared_ptr<const RadialStatistics> base, double zeta_c, LowPassFilter filter) {
    require_positive(zeta_c, "cutoff frequency");
    PsdSplit split;
    split.zeta_c = zeta_c;
    const double sigma2 = base->sigma_h() * base->sigma_h();
    if (filter == LowPassFilter::sharp) {
        split.sigma2_macro = sigma2 * base->radial_cdf(zeta_c);
        split.slope2_macro = base->mean_square_slope(0.0, zeta_c);
    } else {
        // |H|^2 = 2^{-2 (zeta/zeta_c)^2} = exp(-s^2 zeta^2) with s^2 = 2 ln 2 / zeta_c^2: a Gaussian smoothing.
        const double s = std::sqrt(2.0 * std::log(2.0)) / zeta_c;
        split.slope2_macro = base->mean_square_slope(s, std::numeric_limits<double>::infinity());
        const double y_max = std::log(zeta_c) + std::log(40.0);
        split.sigma2_macro = sigma2 * base->radial_cdf(zeta_c * 1e-6) +
                             math::integrate_adaptive(
                                 [&](double y) {
                                     const double z = std::exp(y);
                                     return 2.0 * kPi * z * z * base->psd(z) * low_pass_transfer(filter, z, zeta_c);
                                 },
                                 std::log(zeta_c * 1e-6), y_max, 1e-11);
    }
    split.sigma2_micro = sigma2 - split.sigma2_macro;
    if (filter == LowPassFilter::sharp) {
        if (1.0 - base->radial_cdf(zeta_c) >= kMinCutFraction)
            split.micro = std::make_shared<SharpCutStatistics>(base, zeta_c, CutPart::high_pass);
    }
    else
        split.micro = std::make_shared<GaussianFilteredStatistics>(base, zeta_c, true);
    return split;
}

EllipticalPsdSplit split_elliptical_psd(const EllipticalStatistics& stats, double zeta_c) {
    require_positive(zeta_c, "cutoff frequency");
    EllipticalPsdSplit split;
    const double s = stats.stretch();
    split.cut_stretched = zeta_c * std::min(1.0, s);
    const RadialStatistics& radial = stats.radial();
    const double sigma2 = radial.sigma_h() * radial.sigma_h();
    split.sigma2_macro = sigma2 * radial.radial_cdf(split.cut_stretched);
    split.sigma2_micro = sigma2 - split.sigma2_macro;
    const double half = 0.5 * radial.mean_square_slope(0.0, split.cut_stretched);
    split.slope_variances_lay = Vec2(half, half / (s * s));
    const auto micro = std::make_shared<SharpCutStatistics>(stats.radial_ptr(), split.cut_stretched, CutPart::high_pass);
    // The micro part's own correlation length times s: the same stretch.
    split.micro = std::make_shared<EllipticalStatistics>(micro, s * micro->correlation_length(), stats.lay_angle());
    return split;
}

}  // namespace surfscatter::surface
