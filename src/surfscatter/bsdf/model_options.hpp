#pragma once
// Every option of the scattering models, with one name per option shared by the CLI (kebab-case: --corr-length),
// the renderer's XML plugins, studies, Python and this struct (snake_case: corr_length). Values of the enumerations
// (model names included) have one spelling everywhere, the scene plugins' snake_case (docs/CONVENTIONS.md, "Names");
// the parse_* functions accept the old spellings (kebab-case values such as "ghs-ssa", the CLI's "ggx") and report
// them through deprecated() (core/deprecation.hpp).
// Units: wavelengths in nm, surface lengths (sigma, corr_length, smoothing) in micrometres.
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "surfscatter/heightmap/line_scan.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/profile_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::bsdf {

enum class ModelKind { ghs, ghs_ssa, ggx, two_scale };  // ggx: GGX from statistics, named ggx_stats
enum class GhsMethod { exact, refit };                   // exact: tabulated S_g; refit: Poisson series of KC refits
enum class Truncation { three_sigma, poisson_mass };     // which orders the refit series keeps
enum class FresnelMode { incident, half, rr };           // R(theta_i), F(theta_d), Rayleigh-Rice Q (THEORY 1.3)
enum class SsaForm { energy, strict };                   // THEORY 1.4
enum class AlphaFrom { none, measured, smoothed, kc_link };  // GGX roughness: given, or from the surface (THEORY 4)
enum class MacroNdf { ggx, beckmann };                   // two-scale macro-roughness NDF
enum class PsdKind { kc, gaussian, file, measured };     // surface statistics: KC, Gaussian ACV, KC fitted to a height
                                                         // map, or the map's own radial PSD
enum class PsdFit { isotropic, elliptical };             // psd file: the KC fitted to the map, radial or elliptical
enum class MeasuredSpectrum { two_d, ring };             // psd measured: the map's 2-D spectrum, or its ring average

struct SurfaceOptions {
    PsdKind psd = PsdKind::kc;
    double sigma = 0;         // rms height, um (kc, gaussian)
    double corr_length = 0;   // um: KC L, or Gaussian l in C = sigma^2 exp(-r^2/l^2)
    double gamma = 0;         // KC exponent, > 1
    // Elliptical statistics (psd kc or gaussian; surface::EllipticalStatistics): corr_length is LU along the lay
    // direction u, corr_length_v LV across it (0: LV = LU, isotropic), lay_angle A in degrees from x (phi = 0)
    // towards y in the local frame.
    double corr_length_v = 0;
    double lay_angle = 0;
    std::string surface_file; // height map (psd = file or measured): any format read_height_map reads
    // How the map is prepared (heightmap/prepare.hpp: outliers, form), once, before anything is taken from it.
    heightmap::Preparation preparation;
    bool preparation_noted = false;  // the caller reported the map's preparation (a scene, validity): make_bsdf does not
    // psd file only: the isotropic KC fit (kc_fit.hpp), or the elliptical one (elliptical_fit.hpp), whose LU, LV and
    // lay angle make the statistics elliptical as corr_length_v and lay_angle do for psd kc.
    PsdFit psd_fit = PsdFit::isotropic;
    // A map in memory (Python's HeightMap) to prepare instead of reading surface_file (which then names it).
    std::shared_ptr<const heightmap::HeightMap> height_map;
    // The map prepared, when the caller has done it already (to report on it, load_height_map()); make_bsdf reads and
    // prepares the map itself otherwise.
    std::shared_ptr<const heightmap::PreparedMap> prepared;
    // psd measured only: a map's statistics estimated already (Python's measured_statistics()), used instead of a map.
    std::shared_ptr<const surface::MapStatistics> measured_psd;
    // psd measured only: a profile's own spectrum as an isotropic surface's (surface/profile_statistics.hpp), used
    // instead of a map; every model reads it as radial statistics (measured_spectrum does not apply).
    std::shared_ptr<const surface::ProfileStatistics> measured_profile;
    // The profile (line scan) surface_file holds, when it holds one: load_height_map reads it instead of a map and
    // makes measured_profile of it (a profile is prepared by its form only, none or plane).
    std::shared_ptr<const heightmap::LineScan> profile;
    // psd measured only: 2d, the models ghs (exact) and ghs_ssa on the map's 2-D periodogram (bsdf/map_ghs.hpp) and
    // ggx_stats on the map's slope covariance (alpha_u, alpha_v, lay angle); ring, the ring average and the isotropic
    // rms slope as before. two_scale takes the ring average either way (its note says so).
    MeasuredSpectrum measured_spectrum = MeasuredSpectrum::two_d;
};

struct ModelOptions {
    ModelKind model = ModelKind::ghs;
    // GHS
    GhsMethod method = GhsMethod::exact;
    Truncation truncation = Truncation::three_sigma;  // refit only; the paper's rule
    double epsilon = 1e-6;                            // poisson_mass: dropped Poisson mass
    FresnelMode fresnel = FresnelMode::incident;
    bool renormalization = true;                      // false: sigma_h instead of sigma_rel and K = 1
    // SSA
    SsaForm ssa_form = SsaForm::energy;
    // GGX
    double alpha = 0;                                 // used when alpha_from = none
    AlphaFrom alpha_from = AlphaFrom::measured;       // from the surface unless alpha is given (imply_alpha_from)
    double smoothing = 0;                             // um, Gaussian smoothing std (alpha_from = smoothed)
    // two-scale
    double cutoff_wavelengths = 100;                  // N: macro/micro split at zeta_c = k / N
    MacroNdf macro_ndf = MacroNdf::ggx;
    // material and surface
    std::string material = "perfect";                 // built-in metal, refractiveindex.info/CSV path, or "perfect"
    SurfaceOptions surface;
};

// Parse an enumeration value as written in the CLI, XML, a study or Python; throw surfscatter::Error naming `what`
// and listing the valid values otherwise ("--model must be one of ghs | ghs_ssa | ggx_stats | two_scale, got 'x'").
ModelKind parse_model(std::string_view text, const char* what = "model");
// The model `text` names, or nullopt if it names none (a scene's other BSDF plugins, a -D model=conductor).
std::optional<ModelKind> find_model(std::string_view text, const char* what = "model");
GhsMethod parse_method(std::string_view text, const char* what = "method");
Truncation parse_truncation(std::string_view text, const char* what = "truncation");
FresnelMode parse_fresnel(std::string_view text, const char* what = "fresnel");
SsaForm parse_ssa_form(std::string_view text, const char* what = "ssa_form");
AlphaFrom parse_alpha_from(std::string_view text, const char* what = "alpha_from");
MacroNdf parse_macro_ndf(std::string_view text, const char* what = "macro_ndf");
PsdKind parse_psd(std::string_view text, const char* what = "psd");
PsdFit parse_psd_fit(std::string_view text, const char* what = "psd_fit");
MeasuredSpectrum parse_measured_spectrum(std::string_view text, const char* what = "measured_spectrum");

// The valid values of the enumerated option `name` ("model", "method", "truncation", "fresnel", "ssa_form",
// "alpha_from", "macro_ndf", "psd", "psd_fit", "measured_spectrum") as "a | b | c", for help texts.
std::string choices(std::string_view name);

// A given alpha without alpha_from means alpha_from none, as KC parameters without psd mean psd kc: the rule every
// front end applies before validate().
void imply_alpha_from(ModelOptions& options, bool alpha_given, bool alpha_from_given);

// Why the option `name` (snake_case, as in ModelOptions: "smoothing", "surface_file", "renormalization") has no
// effect for the model and modes of `options`, as a phrase such as "used with alpha_from smoothed only"; empty if it
// takes effect or is not a model option. The CLI and the scene loader turn a non-empty answer into an error naming
// the option as the user wrote it, so that no option is silently ignored.
std::string inapplicable_option(const ModelOptions& options, std::string_view name);

// Canonical (snake_case) names.
std::string to_string(ModelKind v);
std::string to_string(GhsMethod v);
std::string to_string(Truncation v);
std::string to_string(FresnelMode v);
std::string to_string(SsaForm v);
std::string to_string(AlphaFrom v);
std::string to_string(MacroNdf v);
std::string to_string(PsdKind v);
std::string to_string(PsdFit v);
std::string to_string(MeasuredSpectrum v);

}  // namespace surfscatter::bsdf
