#pragma once
// One-dimensional forms of the GHS, SSA and Kirchhoff models (docs/MODELS.md "One-dimensional forms", THEORY 7.3):
// the scattering of a plane wave by a random profile z = h(x), a cut through isotropic statistics, in the geometry
// of `reference exact-1d` (light in the x-z plane arriving from negative x, specular at theta_o = +theta_i), as the
// power per radian of scattering angle over the incident power, so that each theory can be compared with the exact
// solution on the same surface, wavelength and polarisation.
//
// With zeta = k (sin theta_o - sin theta_i), g = (k sigma (cos i + cos o))^2 and rho(x) = C(|x|) / sigma_h^2 the
// profile's normalised ACV (the isotropic C read along the cut):
//   S_g(zeta) = (2 pi)^-1 int e^{-g} (e^{g rho(x)} - 1) e^{-i zeta x} dx = e^{-g} sum_{m>=1} g^m/m! P1^{*m}(zeta)
//   GHS:       I = F K cos(o) k S_g(zeta),                      coherent R(i) e^{-g0}
//   SSA:       energy I = F K1 (1 - e^{-g}) cos(o) k P1-hat(zeta); strict I = F cos(o) k g_h P1-hat(zeta)
//   Kirchhoff: I = R(theta_d) k S_g(zeta) (1 + cos(i + o))^2 / (cos(i) (cos i + cos o)^2), sigma_h, coherent R e^{-g0}
// with K, K1 making the albedo exactly R(theta_i) (`renormalization`; sigma the 1-D relevant roughness, the profile
// PSD's mass over the visible interval zeta in [-k (1 + sin i), k (1 - sin i)]) and F the Fresnel factor of the chosen
// polarisation (incident |r(theta_i)|^2, half |r(theta_d)|^2 with theta_d = |theta_i + theta_o| / 2, rr |Q_ss|^2 or
// |Q_pp|^2 in the plane of incidence). P1-hat = surface::profile_psd / sigma_h^2.
//
// Accuracy: S_g by composite 16-point Gauss-Legendre quadrature of the ACV integral (panels graded by 2 toward x = 0
// from 1e-24 L, then at most min(L / 2, 2 pi / zeta_max) wide out to where rho < 1e-17): within 1e-9 of S_g(0) over
// |zeta| <= zeta_max for g from 0.05 to 3000 (measured 1.8e-13, KC gamma 1.5 and 3, Gaussian ACV;
// ProfileLobes.LobeMatchesAdaptiveQuadrature); its first order is the closed 1-D KC PSD to 1e-13 of the peak plus
// 1e-8 relative (ProfileLobes.FirstOrderIsTheKcProfilePsd). K, K1 and sigma_rel by adaptive Gauss-Kronrod to 1e-10:
// coherent + integral of I = R(theta_i) within 1e-8 (measured 1.2e-12, ProfileLobes.GhsConservesEnergy). Values below
// zero from the quadrature's round-off (|I| < 1e-12 of the peak) are returned as 0; a non-finite value throws.
// Cost (bench_bsdf BM_profile_lobe, docs/PERFORMANCE.md): one S_g is ~(1300 + 16 x 40 L / min(L / 2, 2 pi / zeta_max))
// exponentials and cosines; a 1801-angle GHS lobe with its K at 550 nm 0.10 / 0.22 / 0.84 CPU s for KC L = 0.5 / 2 /
// 8 um (Kirchhoff 0.07-0.53, SSA 0.01), growing as L / lambda.
// Bad input throws Error: a wavelength outside [0.1, 1e8] nm, theta_i outside [0, 90) deg, theta_o outside
// [-90, 90] deg or more than kMaxListItems of them, statistics whose ACV does not decay, a correlation length needing
// more than 1e6 panels (~1e5 wavelengths), a renormalised lobe with no mass over the visible directions.
#include <optional>
#include <string_view>
#include <vector>

#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::bsdf {

enum class ProfileModel { ghs, ghs_ssa, kirchhoff };
enum class ProfilePolarisation { s, p };  // s: E along y (TE); p: H along y (TM), as in reference exact-1d

ProfileModel parse_profile_model(std::string_view text, const char* what = "model");
std::string to_string(ProfileModel model);
ProfilePolarisation parse_profile_polarisation(std::string_view text, const char* what = "polarisation");

struct ProfileModelOptions {
    ProfileModel model = ProfileModel::ghs;
    FresnelMode fresnel = FresnelMode::incident;  // ghs, ghs_ssa (Kirchhoff: the facet's |r(theta_d)|^2)
    bool renormalization = true;                  // ghs: sigma_rel and K; false: sigma_h and K = 1
    SsaForm ssa_form = SsaForm::energy;           // ghs_ssa
};

// Why `option` (snake_case: "fresnel", "renormalization", "ssa_form") has no effect for any of `models`, or empty if
// one of them uses it: the CLI and Python refuse such an option rather than ignore it.
std::string inapplicable_profile_option(const std::vector<ProfileModel>& models, std::string_view option);

struct ProfileLobe {
    std::vector<double> intensity_per_rad;  // the incoherent part at each theta_o
    double coherent = 0;                    // the specular (coherent) fraction of the incident power
    double sigma_um = 0;                    // sigma in g: sigma_rel or sigma_h
    double normalization = 1;               // K (ghs), K1 (ghs_ssa energy), 1 otherwise
    // coherent + the integral of the incoherent part over theta_o in [-90, 90] deg, where the model gives it itself
    // (two_scale: its macro lobe can be narrower than any grid of theta_o); otherwise integrate intensity_per_rad.
    std::optional<double> energy;
};

// (2 pi)^-1 int f(rho(x)) e^{-i zeta x} dx for the profile ACV rho of `statistics`, by the fixed rule above, for
// |zeta| <= zeta_max (rad/um). A PSD with a jump (psd_jump_radius() > 0: the high-pass part of a sharp cut, whose ACV
// rings and decays as x^-3/2) has its first order read from the PSD (surface::profile_psd) and only the orders >= 2
// from the ACV, out to where the ringing's envelope falls below 1e-3 and then tapered (cos^2) to 0 over as long again
// (docs/MODELS.md "One-dimensional forms", two_scale); `statistics` must then outlive the transform.
class ProfileAcvTransform {
public:
    ProfileAcvTransform(const surface::RadialStatistics& statistics, double zeta_max);
    double lobe(double g, double zeta) const;  // S_g(zeta), um
    double order(int m, double zeta) const;    // P1-hat^{*m}(zeta), um; m >= 1
    std::size_t nodes() const { return x_.size(); }

private:
    template <typename F>
    double transform(F&& f, double zeta) const;
    double first_order(double zeta) const;  // P1-hat(zeta) of psd_
    std::vector<double> x_, weight_, rho_;
    const surface::RadialStatistics* psd_ = nullptr;  // a PSD with a jump: its first order read from it
};

// The 1-D relevant roughness: sigma_rel^2 = int P1 over zeta in [-k (1 + sin i), k (1 - sin i)], um.
double profile_relevant_roughness(const surface::RadialStatistics& statistics, double theta_i_rad, double lambda_nm);

// theta_o = -90 + 180 j / steps degrees, j = 0..steps, in radians: with steps = reference::kFarFieldSteps, the grid
// of exact-1d's far field, value for value.
std::vector<double> uniform_theta_grid(int steps);

// Throws Error naming `name` (the caller's option: --wavelength, wavelength_nm) unless lambda_nm is within the 1-D
// models' range, 0.1 nm to 1e8 nm (as the 2-D models'); every lobe below checks it under the plain word.
void require_profile_wavelength(double lambda_nm, const std::string& name);

// The lobe at each theta_o_rad (in [-pi/2, pi/2]).
ProfileLobe profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                         double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                         const ProfileModelOptions& options, const std::vector<double>& theta_o_rad);

// GGX from statistics in one dimension (docs/MODELS.md "One-dimensional forms", "GGX from statistics"): the cut
// through the plane of incidence of ggx_stats' GGX (alpha = the rms slope sqrt(<|grad h|^2>) of `statistics`), in
// geometric optics, with b = (theta_o - theta_i) / 2 the facet's tilt and theta_d = (theta_i + theta_o) / 2 the
// local incidence:
//   I(theta_o) = F(theta_d) G2 P2(tan b) cos(theta_d) / (2 cos^3(b) cos(theta_i)),
// P2(p) = 1 / (2 alpha (1 + p^2 / alpha^2)^(3/2)) the density of the slope along x (GGX's slope density integrated
// over the slope along y), G2 = 1 / (1 + Lambda(i) + Lambda(o)), Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2, F the
// chosen polarisation's |r|^2. No coherent part. Closed forms: round-off only. Throws Error where the rms slope
// diverges (KC gamma <= 3), as ggx_stats does, or for bad input as profile_lobe.
ProfileLobe ggx_profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                             double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                             const std::vector<double>& theta_o_rad);

// two_scale in one dimension (docs/MODELS.md "One-dimensional forms", "two_scale"): the cut through the plane of
// incidence of two_scale.hpp's model with its sharp split at zeta_c = k_ref / cutoff_wavelengths (k_ref at
// kTwoScaleReferenceWavelength, 550 nm) and its GGX macro NDF:
//   I(theta_o) = e^{-g0,micro} I_GGX(theta_o; alpha^2 = <|grad h_LP|^2>) + I_GHS,micro(theta_o),
// I_GGX ggx_profile_lobe's form with the low-pass part's rms slope, I_GHS,micro profile_lobe's renormalised GHS of
// the high-pass part (surface::SharpCutStatistics; its first order from the PSD, ProfileAcvTransform), e^{-g0,micro}
// = its coherent fraction, which the macro facets spread: no coherent part. `energy`: R(theta_i) (1 - e^{-g0,micro})
// (the micro GHS's, exact by K) + e^{-g0,micro} x the GGX lobe's integral (adaptive, 1e-10). Without micro roughness (less than
// surface::kMinCutFraction of the variance above zeta_c) the GGX lobe alone, of weight 1. Accuracy: the GHS's near
// its tests' measured bounds (test_profile_lobes.cpp, TwoScale*). Throws Error for bad input as profile_lobe, a
// cutoff_wavelengths not finite and > 0, or a low-pass part without slope.
ProfileLobe two_scale_profile_lobe(const surface::RadialStatistics& statistics, const material::Conductor& conductor,
                                   double lambda_nm, double theta_i_rad, ProfilePolarisation polarisation,
                                   const std::vector<double>& theta_o_rad, double cutoff_wavelengths = 100);

}  // namespace surfscatter::bsdf
