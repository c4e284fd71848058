#include "surfscatter/bsdf/model_options.hpp"

#include <algorithm>
#include <optional>
#include <span>
#include <utility>

#include <fmt/format.h>

#include "surfscatter/core/deprecation.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

namespace {

// Kebab-case (the CLI's old spelling of values: ghs-ssa, three-sigma) read as snake_case.
std::string snake_case(std::string_view text) {
    std::string s(text);
    std::replace(s.begin(), s.end(), '-', '_');
    return s;
}

template <typename E>
struct Names {
    std::span<const std::pair<const char*, E>> canonical;
    std::span<const std::pair<const char*, const char*>> aliases;  // old spelling -> canonical name
};

template <typename E>
std::string list_of(const Names<E>& names) {
    std::string list;
    for (const auto& [name, value] : names.canonical) list += (list.empty() ? "" : " | ") + std::string(name);
    return list;
}

// The value `text` names, canonical or an old spelling (reported through deprecated()); nullopt if none.
template <typename E>
std::optional<E> find_enum(std::string_view text, const char* what, const Names<E>& names) {
    const std::string s = snake_case(text);
    std::string name = s;
    for (const auto& [alias, target] : names.aliases)
        if (s == alias) name = target;
    for (const auto& [canonical, value] : names.canonical)
        if (name == canonical) {
            if (text != canonical)
                deprecated(fmt::format("{} '{}' is an old spelling: write '{}' (docs/CONVENTIONS.md)", what,
                                       printable(text), canonical));
            return value;
        }
    return std::nullopt;
}

template <typename E>
E parse_enum(std::string_view text, const char* what, const Names<E>& names) {
    if (const auto value = find_enum(text, what, names)) return *value;
    fail("{} must be one of {}, got '{}'", what, list_of(names), printable(text));
}

template <typename E>
std::string enum_name(E v, const Names<E>& names) {
    for (const auto& [name, value] : names.canonical)
        if (v == value) return name;
    return "?";
}

// The one vocabulary of docs/CONVENTIONS.md: the scene plugins' names (snake_case) everywhere.
constexpr std::pair<const char*, ModelKind> kModelNames[]{{"ghs", ModelKind::ghs},
                                                          {"ghs_ssa", ModelKind::ghs_ssa},
                                                          {"ggx_stats", ModelKind::ggx},
                                                          {"two_scale", ModelKind::two_scale}};
// The CLI's and Python's name for GGX from statistics until the names were made one.
constexpr std::pair<const char*, const char*> kModelAliases[]{{"ggx", "ggx_stats"}};
constexpr std::pair<const char*, GhsMethod> kMethods[]{{"exact", GhsMethod::exact}, {"refit", GhsMethod::refit}};
constexpr std::pair<const char*, Truncation> kTruncations[]{{"three_sigma", Truncation::three_sigma},
                                                            {"poisson_mass", Truncation::poisson_mass}};
constexpr std::pair<const char*, FresnelMode> kFresnel[]{
    {"incident", FresnelMode::incident}, {"half", FresnelMode::half}, {"rr", FresnelMode::rr}};
constexpr std::pair<const char*, SsaForm> kSsaForms[]{{"energy", SsaForm::energy}, {"strict", SsaForm::strict}};
constexpr std::pair<const char*, AlphaFrom> kAlphaFrom[]{{"none", AlphaFrom::none},
                                                         {"measured", AlphaFrom::measured},
                                                         {"smoothed", AlphaFrom::smoothed},
                                                         {"kc_link", AlphaFrom::kc_link}};
constexpr std::pair<const char*, MacroNdf> kMacroNdf[]{{"ggx", MacroNdf::ggx}, {"beckmann", MacroNdf::beckmann}};
constexpr std::pair<const char*, PsdKind> kPsd[]{
    {"kc", PsdKind::kc}, {"gaussian", PsdKind::gaussian}, {"file", PsdKind::file}, {"measured", PsdKind::measured}};
constexpr std::pair<const char*, PsdFit> kPsdFit[]{{"isotropic", PsdFit::isotropic}, {"elliptical", PsdFit::elliptical}};
constexpr std::pair<const char*, MeasuredSpectrum> kMeasuredSpectrum[]{{"2d", MeasuredSpectrum::two_d},
                                                                       {"ring", MeasuredSpectrum::ring}};

constexpr Names<ModelKind> kModels{kModelNames, kModelAliases};
template <typename E, std::size_t N>
constexpr Names<E> names(const std::pair<const char*, E> (&table)[N]) {
    return {table, {}};
}

}  // namespace

ModelKind parse_model(std::string_view t, const char* what) { return parse_enum(t, what, kModels); }
std::optional<ModelKind> find_model(std::string_view t, const char* what) { return find_enum(t, what, kModels); }
GhsMethod parse_method(std::string_view t, const char* what) { return parse_enum(t, what, names(kMethods)); }
Truncation parse_truncation(std::string_view t, const char* what) { return parse_enum(t, what, names(kTruncations)); }
FresnelMode parse_fresnel(std::string_view t, const char* what) { return parse_enum(t, what, names(kFresnel)); }
SsaForm parse_ssa_form(std::string_view t, const char* what) { return parse_enum(t, what, names(kSsaForms)); }
AlphaFrom parse_alpha_from(std::string_view t, const char* what) { return parse_enum(t, what, names(kAlphaFrom)); }
MacroNdf parse_macro_ndf(std::string_view t, const char* what) { return parse_enum(t, what, names(kMacroNdf)); }
PsdKind parse_psd(std::string_view t, const char* what) { return parse_enum(t, what, names(kPsd)); }
PsdFit parse_psd_fit(std::string_view t, const char* what) { return parse_enum(t, what, names(kPsdFit)); }
MeasuredSpectrum parse_measured_spectrum(std::string_view t, const char* what) {
    return parse_enum(t, what, names(kMeasuredSpectrum));
}

std::string choices(std::string_view option) {
    if (option == "model") return list_of(kModels);
    if (option == "method") return list_of(names(kMethods));
    if (option == "truncation") return list_of(names(kTruncations));
    if (option == "fresnel") return list_of(names(kFresnel));
    if (option == "ssa_form") return list_of(names(kSsaForms));
    if (option == "alpha_from") return list_of(names(kAlphaFrom));
    if (option == "macro_ndf") return list_of(names(kMacroNdf));
    if (option == "psd") return list_of(names(kPsd));
    if (option == "psd_fit") return list_of(names(kPsdFit));
    if (option == "measured_spectrum") return list_of(names(kMeasuredSpectrum));
    fail("choices: '{}' is not an enumerated model option", printable(option));
}

void imply_alpha_from(ModelOptions& o, bool alpha_given, bool alpha_from_given) {
    if (alpha_given && !alpha_from_given) o.alpha_from = AlphaFrom::none;
}

std::string inapplicable_option(const ModelOptions& o, std::string_view name) {
    const ModelKind m = o.model;
    const bool ghs = m == ModelKind::ghs, ggx = m == ModelKind::ggx;
    const bool refit = ghs && o.method == GhsMethod::refit;
    const bool with_surface = !ggx || o.alpha_from != AlphaFrom::none;
    const PsdKind psd = o.surface.psd;
    const bool from_map = psd == PsdKind::file || psd == PsdKind::measured;
    const auto unless = [](bool applies, const char* why) { return applies ? std::string() : std::string(why); };
    if (name == "method") return unless(ghs, "used by model ghs only");
    if (name == "truncation") return unless(refit, "used by model ghs with method refit only");
    if (name == "epsilon")
        return unless(refit && o.truncation == Truncation::poisson_mass,
                      "used by model ghs with method refit and truncation poisson_mass only");
    if (name == "fresnel") return unless(!ggx, "used by models ghs, ghs_ssa and two_scale only");
    if (name == "renormalization") return unless(ghs || m == ModelKind::two_scale, "used by models ghs and two_scale only");
    if (name == "ssa_form") return unless(m == ModelKind::ghs_ssa, "used by model ghs_ssa only");
    if (name == "alpha") return unless(ggx && o.alpha_from == AlphaFrom::none, "used by model ggx_stats with alpha_from none only");
    if (name == "alpha_from") return unless(ggx, "used by model ggx_stats only");
    if (name == "smoothing") return unless(ggx && o.alpha_from == AlphaFrom::smoothed, "used with alpha_from smoothed only");
    if (name == "cutoff_wavelengths" || name == "macro_ndf") return unless(m == ModelKind::two_scale, "used by model two_scale only");
    if (name == "measured_spectrum") {
        if (!with_surface) return "model ggx_stats with alpha_from none takes no surface";
        if (o.surface.measured_profile)
            return "a profile's 2-D PSD is isotropic by assumption: its 2-D spectrum and its ring average are one";
        return unless(psd == PsdKind::measured, "used with psd measured only");
    }
    if (name == "psd" || name == "sigma" || name == "corr_length" || name == "gamma" || name == "surface_file" ||
        name == "form" || name == "outliers" || name == "row_alignment" || name == "lambda_s" || name == "lambda_c" ||
        name == "corr_length_v" || name == "lay_angle" || name == "psd_fit") {
        if (!with_surface) return "model ggx_stats with alpha_from none takes no surface";
        if (name == "sigma" || name == "corr_length")
            return unless(!from_map, "a height map gives its own statistics (psd file or measured)");
        if (name == "gamma") return unless(psd == PsdKind::kc, "used with psd kc only");
        if (name == "corr_length_v" || name == "lay_angle")
            if (from_map) return "used with psd kc or gaussian only (a height map gives its own statistics)";
        if (name == "lay_angle")
            // 0 is every front end's default (scenes pass it through -D defaults): only a turned lay needs LV.
            return unless(o.surface.corr_length_v != 0 || o.surface.lay_angle == 0,
                          "used with corr_length_v only (without it the surface is isotropic)");
        if (name == "surface_file" || name == "form" || name == "outliers" || name == "row_alignment" ||
            name == "lambda_s" || name == "lambda_c")
            return unless(from_map, "used with a height map (psd file or measured) only");
        if (name == "psd_fit") return unless(psd == PsdKind::file, "used with psd file (the KC fitted to a height map) only");
    }
    return {};
}

std::string to_string(ModelKind v) { return enum_name(v, kModels); }
std::string to_string(GhsMethod v) { return enum_name(v, names(kMethods)); }
std::string to_string(Truncation v) { return enum_name(v, names(kTruncations)); }
std::string to_string(FresnelMode v) { return enum_name(v, names(kFresnel)); }
std::string to_string(SsaForm v) { return enum_name(v, names(kSsaForms)); }
std::string to_string(AlphaFrom v) { return enum_name(v, names(kAlphaFrom)); }
std::string to_string(MacroNdf v) { return enum_name(v, names(kMacroNdf)); }
std::string to_string(PsdKind v) { return enum_name(v, names(kPsd)); }
std::string to_string(PsdFit v) { return enum_name(v, names(kPsdFit)); }
std::string to_string(MeasuredSpectrum v) { return enum_name(v, names(kMeasuredSpectrum)); }

}  // namespace surfscatter::bsdf
