// surfscatter's own BSDFs: `ghs` (full generalised Harvey-Shack), `ghs_ssa` (its smooth-surface approximation),
// `ggx_stats` (GGX with alpha from the surface statistics) and `two_scale` (bsdf/factory.hpp, THEORY.md). They are
// ordinary BSDF plugins: usable wherever a BSDF is (shapes, twosided, blendbsdf, mask, bumpmap, normalmap).
//
// Parameters (bsdf/model_options.hpp, the same names as the CLI): `material`, `psd`, `sigma`, `corr_length`,
// `gamma`, `surface_file` (any height map format, read once per scene and reported with its valid fraction),
// `form`, `fresnel` (all but two_scale's macro part), ghs and two_scale: `method`, `truncation`,
// `epsilon`, `renormalization`; ghs_ssa: `ssa_form`; ggx_stats: `alpha_from`, `smoothing`,
// `alpha`; two_scale: `cutoff_wavelengths`, `macro_ndf`. A parameter the model and modes chosen do not use is an
// error at its line (bsdf::inapplicable_option: e.g. `smoothing` without alpha_from smoothed).
// The models are evaluated for the four wavelengths of a path in one call (Bsdf::eval_packet). One-sided (use
// twosided).
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/render/model_parameters.hpp"
#include "surfscatter/render/plugins.hpp"
#include "surfscatter/surface/height_map_form.hpp"

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

void read_surface_options(Properties& props, bsdf::ModelOptions& o) {
    o.material = props.get_string("material", o.material);
    const std::string psd = props.get_string("psd", "");
    if (!psd.empty()) o.surface.psd = bsdf::parse_psd(psd);
    o.surface.sigma = props.get_float("sigma", o.surface.sigma);
    o.surface.corr_length = props.get_float("corr_length", o.surface.corr_length);
    o.surface.gamma = props.get_float("gamma", o.surface.gamma);
    if (props.has("surface_file")) {
        o.surface.surface_file = props.get_file("surface_file").string();
        if (psd.empty()) o.surface.psd = bsdf::PsdKind::file;
    }
    const std::string form = props.get_string("form", "");
    if (!form.empty()) o.surface.form = surface::parse_form(form, "form");
    const std::string fresnel = props.get_string("fresnel", "");
    if (!fresnel.empty()) o.fresnel = bsdf::parse_fresnel(fresnel);
}

// An option given in the scene that the model and modes chosen do not use is an error at its line (the CLI's rule).
void check_applicable(Properties& props, const bsdf::ModelOptions& o, const std::string& type) {
    for (const char* name : {"material", "psd", "sigma", "corr_length", "gamma", "surface_file", "form", "fresnel",
                             "method", "truncation", "epsilon", "renormalization", "ssa_form", "alpha_from",
                             "smoothing", "alpha", "cutoff_wavelengths", "macro_ndf"})
        if (props.has(name))
            if (const std::string why = bsdf::inapplicable_option(o, name); !why.empty())
                props.fail_param(name, "parameter '{}' does not apply to bsdf '{}': {}", name, type, why);
}

void read_ghs_options(Properties& props, bsdf::ModelOptions& o) {
    const std::string method = props.get_string("method", "");
    if (!method.empty()) o.method = bsdf::parse_method(method);
    const std::string truncation = props.get_string("truncation", "");
    if (!truncation.empty()) o.truncation = bsdf::parse_truncation(truncation);
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
        if (type == "ggx_stats") {
            o.model = bsdf::ModelKind::ggx;
            o.alpha_from = bsdf::AlphaFrom::measured;
            const std::string from = props.get_string("alpha_from", "");
            if (!from.empty()) o.alpha_from = bsdf::parse_alpha_from(from);
            o.smoothing = props.get_float("smoothing", o.smoothing);
            o.alpha = props.get_float("alpha", o.alpha);
            read_surface_options(props, o);
        } else if (type == "ghs") {
            o.model = bsdf::ModelKind::ghs;
            read_ghs_options(props, o);
            read_surface_options(props, o);
        } else if (type == "ghs_ssa") {
            o.model = bsdf::ModelKind::ghs_ssa;
            const std::string form = props.get_string("ssa_form", "");
            if (!form.empty()) o.ssa_form = bsdf::parse_ssa_form(form);
            o.renormalization = props.get_bool("renormalization", o.renormalization);
            read_surface_options(props, o);
        } else if (type == "two_scale") {
            o.model = bsdf::ModelKind::two_scale;
            o.cutoff_wavelengths = props.get_float("cutoff_wavelengths", o.cutoff_wavelengths);
            const std::string ndf = props.get_string("macro_ndf", "");
            if (!ndf.empty()) o.macro_ndf = bsdf::parse_macro_ndf(ndf);
            read_ghs_options(props, o);
            read_surface_options(props, o);
        } else {
            props.fail("unknown scattering model '{}'", type);
        }
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
        return make_model_material(std::shared_ptr<const bsdf::Bsdf>(std::move(model)));
    } catch (const SceneError&) {
        throw;
    } catch (const Error& e) {
        props.fail("bsdf '{}': {}", type, e.what());
    }
}

}  // namespace surfscatter::render
