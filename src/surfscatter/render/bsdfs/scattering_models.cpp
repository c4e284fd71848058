// surfscatter's own BSDFs: `ghs` (full generalised Harvey-Shack), `ghs_ssa` (its smooth-surface approximation),
// `ggx_stats` (GGX with alpha from the surface statistics, or given: `alpha` alone means alpha_from none) and
// `two_scale` (bsdf/factory.hpp, THEORY.md); old spellings of the names (bsdf::find_model) are accepted with a note. They are
// ordinary BSDF plugins: usable wherever a BSDF is (shapes, twosided, blendbsdf, mask, bumpmap, normalmap).
//
// Parameters (bsdf/model_options.hpp, the same names as the CLI): `material`, `psd`, `sigma`, `corr_length`,
// `corr_length_v` and `lay_angle` (degrees; elliptical statistics, surface/elliptical_statistics.hpp: the lay
// direction u is the shading frame's s = dp/du turned by lay_angle about the normal towards t, so the shape's
// tangent frame orients the lay; docs/RENDERER.md lists each shape's dp/du), `gamma`, `surface_file` (any height map format, read once per scene and reported with its valid fraction),
// `form`, `outliers` (keep | fill, the map's outliers: docs/HEIGHTMAPS.md "Outliers"), `row_alignment` (auto | median |
// none), `lambda_s`, `lambda_c` (ISO 16610-61 nesting indices in um, or none; lambda_c auto by default:
// docs/HEIGHTMAPS.md "Preparation"), `psd_fit` (psd file: isotropic | elliptical, the KC fit of the map), `fresnel` (all but two_scale's macro part), ghs and two_scale: `method`, `truncation`,
// `epsilon`, `renormalization`; ghs_ssa: `ssa_form`; ggx_stats: `alpha_from`, `smoothing`,
// `alpha`; two_scale: `cutoff_wavelengths`, `macro_ndf`. A parameter the model and modes chosen do not use is an
// error at its line (bsdf::inapplicable_option: e.g. `smoothing` without alpha_from smoothed).
// The models are evaluated for the four wavelengths of a path in one call (Bsdf::eval_packet). One-sided (use
// twosided).
#include <algorithm>
#include <optional>
#include <string>
#include <thread>
#include <variant>

#include <fmt/format.h>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/map_ghs.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/model_parameters.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/spectrum/wavelength_sampling.hpp"

namespace surfscatter::render {

namespace {

constexpr int kN = spectrum::kSpectrumSamples;
double lambda_at(const SampledWavelengths& w, int i) { return w.lambda[static_cast<std::size_t>(i)]; }

class ModelMaterial final : public Material {
public:
    explicit ModelMaterial(std::shared_ptr<const bsdf::Bsdf> model) : model_(std::move(model)) {}

    SampledSpectrum eval(const ShadingPoint&, const Vec3& wi, const Vec3& wo, const SampledWavelengths& w,
                         SampledSpectrum* pdf) const override {
        SampledSpectrum f;
        f.v = model_->eval_packet(wi, wo, w.lambda, pdf ? &pdf->v : nullptr);
        return f;
    }

    std::optional<MaterialSample> sample(const ShadingPoint&, const Vec3& wo, const SampledWavelengths& w, double u_lobe,
                                         Vec2 u) const override {
        // The model samples its second argument given the first; the path tracer needs the light direction given
        // the viewer's, so the sampled direction is the light's and f is evaluated as f(light, viewer).
        const auto hero = model_->sample(wo, lambda_at(w, 0), u_lobe, u);
        if (!hero || hero->wo.z <= 0) return std::nullopt;
        MaterialSample s;
        s.wi = hero->wo;
        s.delta = hero->delta;
        if (s.delta) {
            for (int i = 0; i < kN; ++i) {
                s.f[i] = model_->delta_reflectance(s.wi, lambda_at(w, i));
                s.pdf[i] = model_->delta_probability(wo, lambda_at(w, i));
            }
        } else {
            s.f.v = model_->eval_packet(s.wi, wo, w.lambda, &s.pdf.v);
            s.pdf[0] = hero->pdf;  // the sampler's own density (eval_packet's equals it up to round-off)
        }
        if (!(s.pdf[0] > 0)) return std::nullopt;
        return s;
    }

    bool has_continuous_part() const override { return !model_->is_pure_delta(); }

private:
    std::shared_ptr<const bsdf::Bsdf> model_;
};

// An enumerated parameter, parsed by the library's one vocabulary; an old spelling's note names the element's line.
template <typename Parse>
auto read_choice(Properties& props, const std::string& name, Parse parse) -> std::optional<decltype(parse("", ""))> {
    const std::string text = props.get_string(name, "");
    if (text.empty()) return std::nullopt;
    std::string what = props.where(name);  // "file:line" of the element, or "origin: name" for text parameters
    if (!what.ends_with(name)) what += ": " + name;
    try {
        return parse(text, what.c_str());
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        throw SceneError(e.what());  // located already
    }
}

void read_surface_options(Properties& props, bsdf::ModelOptions& o) {
    o.material = props.get_string("material", o.material);
    const auto psd = read_choice(props, "psd", bsdf::parse_psd);
    if (psd) o.surface.psd = *psd;
    o.surface.sigma = props.get_float("sigma", o.surface.sigma);
    o.surface.corr_length = props.get_float("corr_length", o.surface.corr_length);
    o.surface.gamma = props.get_float("gamma", o.surface.gamma);
    o.surface.corr_length_v = props.get_float("corr_length_v", o.surface.corr_length_v);
    o.surface.lay_angle = props.get_float("lay_angle", o.surface.lay_angle);
    if (props.has("surface_file")) {
        o.surface.surface_file = props.get_file("surface_file").string();
        if (!psd) o.surface.psd = bsdf::PsdKind::file;
    }
    if (const auto fit = read_choice(props, "psd_fit", bsdf::parse_psd_fit)) o.surface.psd_fit = *fit;
    const std::string form = props.get_string("form", "");
    if (!form.empty()) o.surface.preparation.form = heightmap::parse_form(form, "form");
    const std::string outliers = props.get_string("outliers", "");
    if (!outliers.empty()) o.surface.preparation.outliers = heightmap::parse_outlier_policy(outliers, "outliers");
    const std::string rows = props.get_string("row_alignment", "");
    if (!rows.empty()) o.surface.preparation.rows = heightmap::parse_row_alignment(rows, "row_alignment");
    // Nesting indices: <float> (um) or <string> ("none"; "auto" for lambda_c; empty: the default).
    const auto nesting_text = [&](const char* name) -> std::optional<std::string> {
        const auto value = props.get_float_or_string(name);
        if (!value) return std::nullopt;
        if (const double* number = std::get_if<double>(&*value)) return fmt::format("{:.17g}", *number);
        const std::string& text = std::get<std::string>(*value);
        if (text.empty()) return std::nullopt;  // a scene's empty default: the library's
        return text;
    };
    if (const auto lambda_s = nesting_text("lambda_s"))
        o.surface.preparation.lambda_s_um = heightmap::parse_lambda_s(*lambda_s, "lambda_s");
    if (const auto lambda_c = nesting_text("lambda_c"))
        o.surface.preparation.lambda_c_um = heightmap::parse_lambda_c(*lambda_c, "lambda_c");
    if (const auto spectrum = read_choice(props, "measured_spectrum", bsdf::parse_measured_spectrum))
        o.surface.measured_spectrum = *spectrum;
    if (const auto fresnel = read_choice(props, "fresnel", bsdf::parse_fresnel)) o.fresnel = *fresnel;
}

// An option given in the scene that the model and modes chosen do not use is an error at its line (the CLI's rule).
void check_applicable(Properties& props, const bsdf::ModelOptions& o, const std::string& type) {
    for (const char* name : {"material", "psd", "sigma", "corr_length", "corr_length_v", "lay_angle", "gamma",
                             "surface_file", "form", "outliers", "row_alignment", "lambda_s", "lambda_c", "psd_fit",
                             "measured_spectrum", "fresnel",
                             "method", "truncation", "epsilon", "renormalization", "ssa_form", "alpha_from",
                             "smoothing", "alpha", "cutoff_wavelengths", "macro_ndf"})
        if (props.has(name))
            if (const std::string why = bsdf::inapplicable_option(o, name); !why.empty())
                props.fail_param(name, "parameter '{}' does not apply to bsdf '{}': {}", name, type, why);
}

void read_ghs_options(Properties& props, bsdf::ModelOptions& o) {
    if (const auto method = read_choice(props, "method", bsdf::parse_method)) o.method = *method;
    if (const auto truncation = read_choice(props, "truncation", bsdf::parse_truncation)) o.truncation = *truncation;
    o.epsilon = props.get_float("epsilon", o.epsilon);
    o.renormalization = props.get_bool("renormalization", o.renormalization);
}

}  // namespace

MaterialPtr make_model_material(std::shared_ptr<const bsdf::Bsdf> model) {
    return std::make_shared<ModelMaterial>(std::move(model));
}

bsdf::ModelOptions scattering_model_options(Properties& props, const std::string& type) {
    bsdf::ModelOptions o;
    try {
        const auto kind = bsdf::find_model(type, (props.where() + ": bsdf type").c_str());
        if (!kind) props.fail("unknown scattering model '{}' (bsdf type must be one of {})", type, bsdf::choices("model"));
        o.model = *kind;
        switch (o.model) {
            case bsdf::ModelKind::ggx: {
                const auto from = read_choice(props, "alpha_from", bsdf::parse_alpha_from);
                if (from) o.alpha_from = *from;
                bsdf::imply_alpha_from(o, props.has("alpha"), from.has_value());
                o.smoothing = props.get_float("smoothing", o.smoothing);
                o.alpha = props.get_float("alpha", o.alpha);
                break;
            }
            case bsdf::ModelKind::ghs: read_ghs_options(props, o); break;
            case bsdf::ModelKind::ghs_ssa:
                if (const auto form = read_choice(props, "ssa_form", bsdf::parse_ssa_form)) o.ssa_form = *form;
                o.renormalization = props.get_bool("renormalization", o.renormalization);
                break;
            case bsdf::ModelKind::two_scale:
                o.cutoff_wavelengths = props.get_float("cutoff_wavelengths", o.cutoff_wavelengths);
                if (const auto ndf = read_choice(props, "macro_ndf", bsdf::parse_macro_ndf)) o.macro_ndf = *ndf;
                read_ghs_options(props, o);
                break;
        }
        read_surface_options(props, o);
        check_applicable(props, o, type);
        bsdf::validate(o);
        props.share_height_map(o.surface);
        return o;
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        props.fail("bsdf '{}': {}", type, e.what());
    }
}

MaterialPtr plugins::scattering_model(Properties& props, const std::string& type) {
    const bsdf::ModelOptions o = scattering_model_options(props, type);
    try {
        std::vector<std::string> notes;
        auto model = bsdf::make_bsdf(o, &notes);
        for (const std::string& note : notes) props.add_note(note);
        // A measured 2-D spectrum's tables, one per wavelength node the render samples: built here, over the
        // machine's cores with their own progress line, not one by one inside the render's.
        if (const auto* map = dynamic_cast<const bsdf::MapGhsBsdf*>(model.get()))
            map->tabulate(spectrum::kSampledLambdaMin, spectrum::kSampledLambdaMax,
                          std::max(1u, std::thread::hardware_concurrency()));
        return make_model_material(std::shared_ptr<const bsdf::Bsdf>(std::move(model)));
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        props.fail("bsdf '{}': {}", type, e.what());
    }
}

}  // namespace surfscatter::render
