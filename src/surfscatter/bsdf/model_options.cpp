#include "surfscatter/bsdf/model_options.hpp"

#include <algorithm>
#include <array>
#include <utility>

#include "surfscatter/core/error.hpp"

namespace surfscatter::bsdf {

namespace {

// CLI spelling (kebab-case) and XML spelling (snake_case) are the same word: compare with '-' read as '_'.
std::string canonical(std::string_view text) {
    std::string s(text);
    std::replace(s.begin(), s.end(), '-', '_');
    return s;
}

template <typename E, std::size_t N>
E parse_enum(std::string_view text, const char* what, const std::array<std::pair<const char*, E>, N>& names) {
    const std::string s = canonical(text);
    for (const auto& [name, value] : names)
        if (s == name) return value;
    std::string list;
    for (const auto& [name, value] : names) list += (list.empty() ? "" : " | ") + std::string(name);
    fail("{} must be one of {}, got '{}'", what, list, text);
}

template <typename E, std::size_t N>
std::string enum_name(E v, const std::array<std::pair<const char*, E>, N>& names) {
    for (const auto& [name, value] : names)
        if (v == value) return name;
    return "?";
}

constexpr std::array<std::pair<const char*, ModelKind>, 4> kModels{
    {{"ghs", ModelKind::ghs}, {"ghs_ssa", ModelKind::ghs_ssa}, {"ggx", ModelKind::ggx},
     {"two_scale", ModelKind::two_scale}}};
constexpr std::array<std::pair<const char*, GhsMethod>, 2> kMethods{
    {{"exact", GhsMethod::exact}, {"refit", GhsMethod::refit}}};
constexpr std::array<std::pair<const char*, Truncation>, 2> kTruncations{
    {{"three_sigma", Truncation::three_sigma}, {"poisson_mass", Truncation::poisson_mass}}};
constexpr std::array<std::pair<const char*, FresnelMode>, 3> kFresnel{
    {{"incident", FresnelMode::incident}, {"half", FresnelMode::half}, {"rr", FresnelMode::rr}}};
constexpr std::array<std::pair<const char*, SsaForm>, 2> kSsaForms{
    {{"energy", SsaForm::energy}, {"strict", SsaForm::strict}}};
constexpr std::array<std::pair<const char*, AlphaFrom>, 4> kAlphaFrom{
    {{"none", AlphaFrom::none}, {"measured", AlphaFrom::measured}, {"smoothed", AlphaFrom::smoothed},
     {"kc_link", AlphaFrom::kc_link}}};
constexpr std::array<std::pair<const char*, MacroNdf>, 2> kMacroNdf{
    {{"ggx", MacroNdf::ggx}, {"beckmann", MacroNdf::beckmann}}};
constexpr std::array<std::pair<const char*, PsdKind>, 4> kPsd{
    {{"kc", PsdKind::kc}, {"gaussian", PsdKind::gaussian}, {"file", PsdKind::file}, {"measured", PsdKind::measured}}};

}  // namespace

ModelKind parse_model(std::string_view t, const char* what) { return parse_enum(t, what, kModels); }
GhsMethod parse_method(std::string_view t, const char* what) { return parse_enum(t, what, kMethods); }
Truncation parse_truncation(std::string_view t, const char* what) { return parse_enum(t, what, kTruncations); }
FresnelMode parse_fresnel(std::string_view t, const char* what) { return parse_enum(t, what, kFresnel); }
SsaForm parse_ssa_form(std::string_view t, const char* what) { return parse_enum(t, what, kSsaForms); }
AlphaFrom parse_alpha_from(std::string_view t, const char* what) { return parse_enum(t, what, kAlphaFrom); }
MacroNdf parse_macro_ndf(std::string_view t, const char* what) { return parse_enum(t, what, kMacroNdf); }
PsdKind parse_psd(std::string_view t, const char* what) { return parse_enum(t, what, kPsd); }

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
    if (name == "alpha") return unless(ggx && o.alpha_from == AlphaFrom::none, "used by model ggx with alpha_from none only");
    if (name == "alpha_from") return unless(ggx, "used by model ggx only");
    if (name == "smoothing") return unless(ggx && o.alpha_from == AlphaFrom::smoothed, "used with alpha_from smoothed only");
    if (name == "cutoff_wavelengths" || name == "macro_ndf") return unless(m == ModelKind::two_scale, "used by model two_scale only");
    if (name == "psd" || name == "sigma" || name == "corr_length" || name == "gamma" || name == "surface_file" ||
        name == "form") {
        if (!with_surface) return "model ggx with alpha_from none takes no surface";
        if (name == "sigma" || name == "corr_length")
            return unless(!from_map, "a height map gives its own statistics (psd file or measured)");
        if (name == "gamma") return unless(psd == PsdKind::kc, "used with psd kc only");
        if (name == "surface_file" || name == "form")
            return unless(from_map, "used with a height map (psd file or measured) only");
    }
    return {};
}

std::string to_string(ModelKind v) { return enum_name(v, kModels); }
std::string to_string(GhsMethod v) { return enum_name(v, kMethods); }
std::string to_string(Truncation v) { return enum_name(v, kTruncations); }
std::string to_string(FresnelMode v) { return enum_name(v, kFresnel); }
std::string to_string(SsaForm v) { return enum_name(v, kSsaForms); }
std::string to_string(AlphaFrom v) { return enum_name(v, kAlphaFrom); }
std::string to_string(MacroNdf v) { return enum_name(v, kMacroNdf); }
std::string to_string(PsdKind v) { return enum_name(v, kPsd); }

}  // namespace surfscatter::bsdf
