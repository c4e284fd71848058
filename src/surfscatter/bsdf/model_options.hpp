#pragma once
// Every option of the scattering models, with one name per option shared by the CLI (kebab-case: --corr-length),
// the renderer's XML plugins and this struct (snake_case: corr_length). Values of the enumerations are spelled
// as in the CLI/XML ("ghs_ssa" and "ghs-ssa" are both accepted by the parse_* functions).
// Units: wavelengths in nm, surface lengths (sigma, corr_length, smoothing) in micrometres.
#include <memory>
#include <string>
#include <string_view>

#include "surfscatter/surface/height_map.hpp"
#include "surfscatter/surface/height_map_form.hpp"

namespace surfscatter::bsdf {

enum class ModelKind { ghs, ghs_ssa, ggx, two_scale };
enum class GhsMethod { exact, refit };                   // exact: tabulated S_g; refit: Poisson series of KC refits
enum class Truncation { three_sigma, poisson_mass };     // which orders the refit series keeps
enum class FresnelMode { incident, half, rr };           // R(theta_i), F(theta_d), Rayleigh-Rice Q (THEORY 1.3)
enum class SsaForm { energy, strict };                   // THEORY 1.4
enum class AlphaFrom { none, measured, smoothed, kc_link };  // GGX roughness: given, or from the surface (THEORY 4)
enum class MacroNdf { ggx, beckmann };                   // two-scale macro-roughness NDF
enum class PsdKind { kc, gaussian, file, measured };     // surface statistics: KC, Gaussian ACV, KC fitted to a height
                                                         // map, or the map's own radial PSD

struct SurfaceOptions {
    PsdKind psd = PsdKind::kc;
    double sigma = 0;         // rms height, um (kc, gaussian)
    double corr_length = 0;   // um: KC L, or Gaussian l in C = sigma^2 exp(-r^2/l^2)
    double gamma = 0;         // KC exponent, > 1
    std::string surface_file; // height map (psd = file or measured): any format read_height_map reads
    surface::Form form = surface::Form::plane;  // removed from the height map before its statistics
    // The map read from surface_file when the caller has read it already (to report on it, load_height_map());
    // make_bsdf reads surface_file itself otherwise.
    std::shared_ptr<const surface::HeightMap> height_map;
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
    AlphaFrom alpha_from = AlphaFrom::none;
    double smoothing = 0;                             // um, Gaussian smoothing std (alpha_from = smoothed)
    // two-scale
    double cutoff_wavelengths = 100;                  // N: macro/micro split at zeta_c = k / N
    MacroNdf macro_ndf = MacroNdf::ggx;
    // material and surface
    std::string material = "perfect";                 // built-in metal, refractiveindex.info/CSV path, or "perfect"
    SurfaceOptions surface;
};

// Parse an enumeration value as written in the CLI or XML; throw surfscatter::Error naming `what` otherwise.
ModelKind parse_model(std::string_view text, const char* what = "model");
GhsMethod parse_method(std::string_view text, const char* what = "method");
Truncation parse_truncation(std::string_view text, const char* what = "truncation");
FresnelMode parse_fresnel(std::string_view text, const char* what = "fresnel");
SsaForm parse_ssa_form(std::string_view text, const char* what = "ssa_form");
AlphaFrom parse_alpha_from(std::string_view text, const char* what = "alpha_from");
MacroNdf parse_macro_ndf(std::string_view text, const char* what = "macro_ndf");
PsdKind parse_psd(std::string_view text, const char* what = "psd");

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

}  // namespace surfscatter::bsdf
