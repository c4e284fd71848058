#pragma once
// Isotropic surface statistics: radial PSD and normalised autocovariance (THEORY.md sections 0 and 2).
// Conventions: zeta is the ANGULAR spatial frequency in rad/um, r a lateral distance in um, heights in um.
// C(r) = int P(zeta) e^{i zeta.r} d2zeta, so int P d2zeta = sigma_h^2; P-hat = P / sigma_h^2 has unit mass over the
// zeta-plane and rho(r) = C(r)/sigma_h^2 = 2 pi H0{P-hat}(r), P-hat = (1/2pi) H0{rho} (hankel.hpp).
// Cyclic frequency f = zeta/(2 pi): PSD_f(f) = 4 pi^2 P(2 pi f).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace surfscatter::surface {

// Accepted surface statistics from the user (docs/RELIABILITY.md): lengths (sigma_h, correlation lengths) from 1 fm
// to 1 km, and KC gamma from 1.01 (below, the self-convolution refit of selfconv and GHS refit loses its fit) to 100.
// The CLI, the scattering models' options and the scene loader check these; the classes below accept the wider
// ranges that internal uses need (refit orders L m^-x, fit iterations) while keeping every value they return
// finite: lengths in [1e-100, 1e100] um, 1 < gamma <= 100 (as gamma nears 343, Gamma(nu) of the ACV's
// normalisation leaves the double range and std::cyl_bessel_k slows down without bound).
inline constexpr double kMinSurfaceLengthUm = 1e-9;
inline constexpr double kMaxSurfaceLengthUm = 1e9;
inline constexpr double kMinKcGamma = 1.01;
inline constexpr double kMaxKcGamma = 100;

// Throw Error "<what> must be between ... got ..." outside the user ranges (also for NaN and infinities).
void require_surface_length(double length_um, const char* what);
void require_kc_gamma(double gamma, const char* what);

class RadialStatistics {
public:
    virtual ~RadialStatistics() = default;

    virtual double sigma_h() const = 0;                 // rms height, um
    virtual double psd_unit(double zeta) const = 0;     // P-hat(zeta), um^2, unit mass over the zeta-plane
    double psd(double zeta) const;                      // P = sigma_h^2 P-hat, um^4
    virtual double acv_normalized(double r) const = 0;  // rho(r) = C(r)/sigma_h^2, rho(0) = 1
    double acv(double r) const;                         // C(r) = sigma_h^2 rho(r), um^2
    virtual double radial_cdf(double zeta) const = 0;   // mass of P-hat inside |zeta'| <= zeta, in [0, 1]
    virtual double correlation_length() const = 0;      // characteristic length (um) that scales tables
    // Stable text naming the model and every parameter that shapes P-hat and rho (sigma_h does not: the tables built
    // from it are unit-mass shapes, shared by all surfaces that differ only in sigma_h).
    virtual std::string cache_key() const = 0;
    // Radius (rad/um) where P-hat jumps (a sharp filter's cut), 0 if P-hat is continuous: the lobe tables add the
    // discontinuous first-order term analytically and quadratures put a break there.
    virtual double psd_jump_radius() const { return 0.0; }

    // <|grad h|^2> = int |zeta|^2 |H(zeta)|^2 P(zeta) d2zeta (dimensionless), with Gaussian smoothing of standard
    // deviation `smoothing_um` (|H|^2 = exp(-s^2 zeta^2); 0 = none) and a sharp low-pass at `cutoff_zeta` (rad/um;
    // +inf = none). Returns +inf when the integral diverges (e.g. KC gamma <= 3 without smoothing or cutoff).
    // Default: adaptive Gauss-Kronrod quadrature in ln(1 + zeta L) up to zeta L = e^100, relative accuracy ~1e-9;
    // +inf if the integrand has not decayed there (tails at least as slow as zeta^-4 count as divergent).
    virtual double mean_square_slope(double smoothing_um, double cutoff_zeta) const;

    // Total integrated scatter of the GHS lobe at normal incidence for wavelength lambda (nm), perfect conductor:
    // 1 - exp(-(4 pi sigma_rel / lambda)^2) with sigma_rel = relevant_roughness(0, lambda) (THEORY.md 1.1).
    double total_integrated_scatter(double theta_i_rad, double lambda_nm) const;
};

// K-correlation ("ABC") model, THEORY.md 2.1-2.2: P-hat = (gamma-1) L^2/(2 pi) (1 + L^2 zeta^2)^(-(gamma+1)/2),
// rho(r) = 2^(1-nu)/Gamma(nu) (r/L)^nu K_nu(r/L), nu = (gamma-1)/2. All closed forms are accurate to ~1e-14
// relative (rho: elementary forms for gamma = 2, 4, 6; std::cyl_bessel_k otherwise, series below r/L = 1e-6).
class KCorrelation final : public RadialStatistics {
public:
    KCorrelation(double sigma_h_um, double corr_length_um, double gamma);  // throws Error unless sigma, L > 0, gamma > 1
    double gamma() const { return gamma_; }
    double sigma_h() const override { return sigma_; }
    double correlation_length() const override { return length_; }
    double psd_unit(double zeta) const override;
    // The profile (1-D) PSD per unit variance, P-hat integrated over zeta_y at zeta_x = zeta (what a line scan of the
    // isotropic surface holds; unit mass over the zeta_x-line): (gamma - 1) L B / (2 pi) (1 + L^2 zeta^2)^(-gamma/2),
    // B = sqrt(pi) Gamma(gamma/2) / Gamma((gamma + 1)/2) (docs/HEIGHTMAPS.md "Profiles").
    double profile_psd_unit(double zeta) const;
    double acv_normalized(double r) const override;
    double radial_cdf(double zeta) const override;  // 1 - (1 + L^2 zeta^2)^(-(gamma-1)/2)
    double inverse_radial_cdf(double u) const;      // zeta with radial_cdf(zeta) = u, u in [0, 1); +inf at u = 1
    // Draw of the 2-D P-hat (bivariate Student-t, THEORY.md 2.1) radius from u in [0,1): = inverse_radial_cdf(u).
    std::string cache_key() const override;
    double mean_square_slope(double smoothing_um, double cutoff_zeta) const override;  // closed forms (4.1, 3.2)

private:
    double sigma_, length_, gamma_, nu_, acv_norm_;
};

// Gaussian ACV C = sigma^2 exp(-r^2/l^2); P-hat = l^2/(4 pi) exp(-l^2 zeta^2/4). Exact closed forms.
class GaussianAcv final : public RadialStatistics {
public:
    GaussianAcv(double sigma_h_um, double corr_length_um);
    double sigma_h() const override { return sigma_; }
    double correlation_length() const override { return length_; }
    double psd_unit(double zeta) const override;
    double acv_normalized(double r) const override;
    double radial_cdf(double zeta) const override;  // 1 - exp(-l^2 zeta^2 / 4)
    double inverse_radial_cdf(double u) const;
    std::string cache_key() const override;
    double mean_square_slope(double smoothing_um, double cutoff_zeta) const override;  // 4 sigma^2/l^2 unfiltered

private:
    double sigma_, length_;
};

// Isotropic statistics defined numerically by a radial P(zeta) function: sigma_h^2 = int P d2zeta, rho = 2pi H0{P-hat}
// computed once by FFTLog on a log grid (256 points per decade, 22 decades around the support) and interpolated
// (cubic in ln r; absolute accuracy ~5e-8, tested against KC). The radial CDF comes from a 4-point cumulative rule
// (~1e-9). The length scale is the inverse median radius of P-hat. Base of TabulatedPsd and GaussianFilteredStatistics.
class NumericalRadialStatistics : public RadialStatistics {
public:
    double sigma_h() const override { return sigma_; }
    double correlation_length() const override { return length_; }
    double psd_unit(double zeta) const override { return psd_raw(zeta) / (sigma_ * sigma_); }
    double acv_normalized(double r) const override;
    double radial_cdf(double zeta) const override;
    std::string cache_key() const override { return key_; }

protected:
    // Call from the derived constructor once psd_raw works: integrates, sets sigma_h, the length scale and tables.
    void initialise(std::string key);
    virtual double psd_raw(double zeta) const = 0;  // P(zeta), um^4 (any overall scale)
    double zeta_lo_ = 0, zeta_hi_ = 0;               // support hints for the quadrature / transform grid (rad/um)

private:
    double sigma_ = 0, length_ = 0;
    std::string key_;
    std::vector<double> log_r_, rho_;             // rho on the FFTLog grid
    double r_valid_lo_ = 0, r_valid_hi_ = 0;      // ln r range away from the transform's ringing ends
    std::vector<double> log_zeta_, cdf_;          // radial CDF on a log grid
};

// Measured radial PSD from samples (zeta_i rad/um strictly increasing, P_i um^4 > 0): log-log linear interpolation
// between samples, flat below zeta_0, power-law tail beyond the last sample with the slope of the last decade
// (must fall faster than zeta^-2 so that sigma is finite; otherwise Error).
class TabulatedPsd final : public NumericalRadialStatistics {
public:
    TabulatedPsd(std::vector<double> zeta, std::vector<double> psd);
    // The data's range (rad/um) and the tail's power (P ~ zeta^tail_slope beyond last_zeta): what is extrapolated.
    double first_zeta() const { return std::exp(log_zeta_samples_.front()); }
    double last_zeta() const { return std::exp(log_zeta_samples_.back()); }
    double tail_slope() const { return tail_slope_; }

private:
    double psd_raw(double zeta) const override;
    std::vector<double> log_zeta_samples_, log_psd_samples_;
    double tail_slope_;
};

// ABC (Church/Dittman) parameters of a KC PSD in CYCLIC frequency (THEORY.md 2.1): PSD_f(f) = A (1 + (B f)^2)^(-(C+1)/2)
// with C = gamma, B = 2 pi L (um), A = sigma^2 B^2 (C-1)/(2 pi) (um^4).
struct AbcParameters {
    double a, b, c;
};
AbcParameters to_abc(const KCorrelation&);
KCorrelation from_abc(const AbcParameters&);
// Cyclic <-> angular frequency conversion of a PSD value: PSD_f(f) = 4 pi^2 P(2 pi f).
inline double cyclic_psd_from_angular(double p_angular) { return 39.47841760435743 * p_angular; }
inline double angular_psd_from_cyclic(double p_cyclic) { return p_cyclic / 39.47841760435743; }

}  // namespace surfscatter::surface
