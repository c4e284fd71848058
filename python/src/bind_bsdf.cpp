// surfscatter.bsdf(...) -> Bsdf: bsdf/factory.hpp and bsdf/model_options.hpp, with eval/sample/pdf/albedo over
// numpy arrays on TBB's threads.
#include <atomic>
#include <cstring>
#include <limits>
#include <optional>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/bsdf/albedo.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/measured_band.hpp"
#include "surfscatter/bsdf/rgl_export.hpp"
#include "surfscatter/bsdf/rgl_measured.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::python {

namespace {

using namespace pybind11::literals;
using bsdf::ModelOptions;

// A model and the options it was built from.
struct PyBsdf {
    std::shared_ptr<const bsdf::Bsdf> model;
    ModelOptions options;
    std::vector<std::string> notes;  // what make_bsdf says about the result (e.g. a measured PSD's extrapolation)
    std::optional<bsdf::MeasuredBand> band;  // psd measured: what eval warns about (bsdf/measured_band.hpp)
};

double number_option(py::handle value, const char* name) {
    if (py::isinstance<py::bool_>(value)) fail("{} must be a number, got {}", name, py::repr(value).cast<std::string>());
    return real_scalar(value, name);
}

// Every keyword option of surfscatter.bsdf, named as in ModelOptions and the XML plugins (docs/MODELS.md).
using Setter = std::function<void(ModelOptions&, py::handle, const char*)>;
const std::map<std::string, Setter>& option_setters() {
    static const std::map<std::string, Setter> setters = {
        {"method", [](ModelOptions& o, py::handle v, const char* n) { o.method = bsdf::parse_method(text_option(v, n), n); }},
        {"truncation",
         [](ModelOptions& o, py::handle v, const char* n) { o.truncation = bsdf::parse_truncation(text_option(v, n), n); }},
        {"epsilon", [](ModelOptions& o, py::handle v, const char* n) { o.epsilon = number_option(v, n); }},
        {"fresnel", [](ModelOptions& o, py::handle v, const char* n) { o.fresnel = bsdf::parse_fresnel(text_option(v, n), n); }},
        {"renormalization",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.renormalization = bool_option(v, n);
         }},
        {"ssa_form", [](ModelOptions& o, py::handle v, const char* n) { o.ssa_form = bsdf::parse_ssa_form(text_option(v, n), n); }},
        {"alpha", [](ModelOptions& o, py::handle v, const char* n) { o.alpha = number_option(v, n); }},
        {"alpha_from",
         [](ModelOptions& o, py::handle v, const char* n) { o.alpha_from = bsdf::parse_alpha_from(text_option(v, n), n); }},
        {"smoothing", [](ModelOptions& o, py::handle v, const char* n) { o.smoothing = number_option(v, n); }},
        {"cutoff_wavelengths", [](ModelOptions& o, py::handle v, const char* n) { o.cutoff_wavelengths = number_option(v, n); }},
        {"macro_ndf",
         [](ModelOptions& o, py::handle v, const char* n) { o.macro_ndf = bsdf::parse_macro_ndf(text_option(v, n), n); }},
        {"psd", [](ModelOptions& o, py::handle v, const char* n) { o.surface.psd = bsdf::parse_psd(text_option(v, n), n); }},
        {"sigma", [](ModelOptions& o, py::handle v, const char* n) { o.surface.sigma = number_option(v, n); }},
        {"corr_length", [](ModelOptions& o, py::handle v, const char* n) { o.surface.corr_length = number_option(v, n); }},
        {"gamma", [](ModelOptions& o, py::handle v, const char* n) { o.surface.gamma = number_option(v, n); }},
        {"corr_length_v", [](ModelOptions& o, py::handle v, const char* n) { o.surface.corr_length_v = number_option(v, n); }},
        {"lay_angle_deg", [](ModelOptions& o, py::handle v, const char* n) { o.surface.lay_angle = number_option(v, n); }},
        {"surface_file", [](ModelOptions& o, py::handle v, const char* n) { o.surface.surface_file = path_string(v, n); }},
        {"form", [](ModelOptions& o, py::handle v, const char* n) { o.surface.preparation.form = heightmap::parse_form(text_option(v, n), n); }},
        {"outliers",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.surface.preparation.outliers = heightmap::parse_outlier_policy(text_option(v, n), n);
         }},
        {"row_alignment",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.surface.preparation.rows = heightmap::parse_row_alignment(text_option(v, n), n);
         }},
        {"lambda_s_um",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.surface.preparation.lambda_s_um = heightmap::parse_lambda_s(nesting_index_text(v, n), n);
         }},
        {"lambda_c_um",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.surface.preparation.lambda_c_um = heightmap::parse_lambda_c(nesting_index_text(v, n), n);
         }},
        {"psd_fit",
         [](ModelOptions& o, py::handle v, const char* n) { o.surface.psd_fit = bsdf::parse_psd_fit(text_option(v, n), n); }},
        {"measured_spectrum",
         [](ModelOptions& o, py::handle v, const char* n) {
             o.surface.measured_spectrum = bsdf::parse_measured_spectrum(text_option(v, n), n);
         }},
    };
    return setters;
}

// The surface= argument: statistics objects and height maps become the SurfaceOptions the XML would give. A height
// map (object or file) is the surface of psd 'file' (KC fitted to it) unless psd 'measured' (its own PSD) was given.
void set_lay(ModelOptions& o, py::handle statistics) {
    const Lay lay = lay_of(statistics);
    o.surface.corr_length_v = lay.corr_length_v;
    o.surface.lay_angle = lay.lay_angle_deg;
}

void set_surface(ModelOptions& o, py::handle value, bool psd_given) {
    const bool statistics = py::isinstance<surface::KCorrelation>(value) || py::isinstance<surface::GaussianAcv>(value) ||
                            py::isinstance<surface::MapStatistics>(value);
    if (statistics && psd_given) fail("psd applies to a height map surface (file or measured), not to {}",
                                      py::repr(value).cast<std::string>());
    if (py::isinstance<surface::KCorrelation>(value)) {
        const auto& kc = value.cast<const surface::KCorrelation&>();
        o.surface.psd = bsdf::PsdKind::kc;
        o.surface.sigma = kc.sigma_h();
        o.surface.corr_length = kc.correlation_length();
        o.surface.gamma = kc.gamma();
        set_lay(o, value);
        return;
    }
    if (py::isinstance<surface::GaussianAcv>(value)) {
        const auto& g = value.cast<const surface::GaussianAcv&>();
        o.surface.psd = bsdf::PsdKind::gaussian;
        o.surface.sigma = g.sigma_h();
        o.surface.corr_length = g.correlation_length();
        set_lay(o, value);
        return;
    }
    if (py::isinstance<surface::MapStatistics>(value)) {  // measured_statistics(map): the map's own PSD
        o.surface.psd = bsdf::PsdKind::measured;
        o.surface.measured_psd = value.cast<std::shared_ptr<surface::MapStatistics>>();
        return;
    }
    if (py::isinstance<heightmap::HeightMap>(value)) {
        const auto map = value.cast<std::shared_ptr<heightmap::HeightMap>>();
        o.surface.surface_file = map->origin();
        o.surface.height_map = map;
    } else if (py::isinstance<py::str>(value) || py::isinstance(value, py::module_::import("os").attr("PathLike"))) {
        o.surface.surface_file = path_string(value, "surface");
    } else {
        fail("surface must be a KCorrelation, a GaussianAcv, a MapStatistics (measured_statistics), a HeightMap or the "
             "path of a height map file, got {}", printable(py::repr(value).cast<std::string>()));
    }
    if (!psd_given) o.surface.psd = bsdf::PsdKind::file;
    else if (o.surface.psd != bsdf::PsdKind::file && o.surface.psd != bsdf::PsdKind::measured)
        fail("a height map surface takes psd 'file' (KC fitted to it, the default) or 'measured' (its own PSD), got "
             "psd '{}'", to_string(o.surface.psd));
}

// A note as a UserWarning (an exception when warnings are errors).
void warn(const std::string& note) {
    if (PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0) throw py::error_already_set();
}

PyBsdf make(const std::string& model, py::handle surface_arg, py::handle material, const py::kwargs& options) {
    ModelOptions o;
    o.model = bsdf::parse_model(model, "model");
    const std::string model_name = bsdf::to_string(o.model);
    o.material = path_string(material, "material");
    const auto& setters = option_setters();
    bool parameter_keywords = false;
    for (const auto& [key, value] : options) {
        const auto name = key.cast<std::string>();
        const auto setter = setters.find(name);
        if (setter == setters.end()) {
            std::string known;
            for (const auto& [option, unused] : setters) known += (known.empty() ? "" : ", ") + option;
            fail("unknown option '{}' (options: model, surface, material, {})", name, known);
        }
        setter->second(o, value, setter->first.c_str());
        parameter_keywords |= name == "sigma" || name == "corr_length" || name == "gamma" || name == "surface_file" ||
                              name == "corr_length_v" || name == "lay_angle_deg";
    }
    const bool psd_given = options.contains("psd");
    bsdf::imply_alpha_from(o, options.contains("alpha"), options.contains("alpha_from"));
    const bool needs_surface = o.model != bsdf::ModelKind::ggx || o.alpha_from != bsdf::AlphaFrom::none;
    if (needs_surface && surface_arg.is_none() && !parameter_keywords)
        fail("bsdf('{}') needs surface=: KCorrelation(sigma, corr_length, gamma), GaussianAcv(sigma, corr_length), "
             "measured_statistics(height_map), a HeightMap or a height map path{}", model_name,
             o.model == bsdf::ModelKind::ggx ? "; or alpha= for a given roughness" : "");
    if (!surface_arg.is_none()) {
        if (parameter_keywords) fail("give either surface= or sigma/corr_length/gamma/surface_file, not both");
        set_surface(o, surface_arg, psd_given);
    } else if (!o.surface.surface_file.empty() && !psd_given) {
        o.surface.psd = bsdf::PsdKind::file;  // as the XML: a surface_file alone is the surface
    }
    // An option the model does not use is an error, as at the CLI and in scenes (never silently ignored).
    std::vector<std::string> given;
    for (const auto& [key, value] : options) given.push_back(key.cast<std::string>());
    if (!surface_arg.is_none()) given.emplace_back("surface");
    for (const std::string& given_name : given)
        if (const std::string why = bsdf::inapplicable_option(
                o, given_name == "surface" ? "psd" : given_name == "lay_angle_deg" ? "lay_angle" : given_name);
            !why.empty())
            fail("{} does not apply to model {}: {}", given_name, model_name, why);
    std::vector<std::string> notes;
    std::shared_ptr<const bsdf::Bsdf> built;
    {
        py::gil_scoped_release release;
        bsdf::validate(o);  // before the map is read, so that a bad option is named first, as without it
        if (needs_surface) bsdf::load_height_map(o.surface);  // prepared once, kept for the band eval warns about
        built = bsdf::make_bsdf(o, &notes);
    }
    for (const std::string& note : notes) warn(note);
    const auto band = needs_surface ? bsdf::measured_band(o.surface) : std::nullopt;
    return {std::move(built), o, std::move(notes), band};
}

py::dict options_dict(const ModelOptions& o) {
    return py::dict("model"_a = to_string(o.model), "material"_a = o.material, "method"_a = to_string(o.method),
                    "truncation"_a = to_string(o.truncation), "epsilon"_a = o.epsilon,
                    "fresnel"_a = to_string(o.fresnel), "renormalization"_a = o.renormalization,
                    "ssa_form"_a = to_string(o.ssa_form), "alpha"_a = o.alpha,
                    "alpha_from"_a = to_string(o.alpha_from), "smoothing"_a = o.smoothing,
                    "cutoff_wavelengths"_a = o.cutoff_wavelengths, "macro_ndf"_a = to_string(o.macro_ndf),
                    "psd"_a = to_string(o.surface.psd), "sigma"_a = o.surface.sigma,
                    "corr_length"_a = o.surface.corr_length, "gamma"_a = o.surface.gamma,
                    "corr_length_v"_a = o.surface.corr_length_v, "lay_angle_deg"_a = o.surface.lay_angle,
                    "surface_file"_a = o.surface.surface_file, "form"_a = heightmap::to_string(o.surface.preparation.form),
                    "outliers"_a = heightmap::to_string(o.surface.preparation.outliers),
                    "psd_fit"_a = to_string(o.surface.psd_fit),
                    "measured_spectrum"_a = to_string(o.surface.measured_spectrum));
}

Vec3 vec(const double* v) { return {v[0], v[1], v[2]}; }

// f(wi, wo, lambda) for eval and pdf.
template <typename F>
py::object pair_map(py::handle wi, py::handle wo, py::handle lambda_nm, const F& f) {
    const Batch batch({{wi, "wi", Domain::unit_vector}, {wo, "wo", Domain::unit_vector},
                       {lambda_nm, "lambda_nm", Domain::wavelength_nm}});
    auto out = batch.output<double>();
    double* values = out.mutable_data();
    if (batch.single(0) && batch.single(2)) {  // one wi and wavelength, many wo (a lobe, a table): read once
        const Vec3 i = vec(batch.at(0, 0));
        const double lambda = *batch.at(2, 0);
        const double* o = batch.at(1, 0);
        batch.for_each([&](std::size_t k) { values[k] = f(i, vec(o + 3 * k), lambda); });
    } else {
        batch.for_each([&](std::size_t k) {
            values[k] = f(vec(batch.at(0, k)), vec(batch.at(1, k)), *batch.at(2, k));
        });
    }
    return result(out);
}

// f(wi, lambda) for the delta lobe's figures.
template <typename F>
py::object incident_map(py::handle wi, py::handle lambda_nm, const F& f) {
    const Batch batch({{wi, "wi", Domain::unit_vector}, {lambda_nm, "lambda_nm", Domain::wavelength_nm}});
    auto out = batch.output<double>();
    double* values = out.mutable_data();
    batch.for_each([&](std::size_t i) { values[i] = f(vec(batch.at(0, i)), *batch.at(1, i)); });
    return result(out);
}

py::tuple sample(const bsdf::Bsdf& model, py::handle wi, py::handle lambda_nm, py::handle u) {
    const Batch batch({{wi, "wi", Domain::unit_vector}, {lambda_nm, "lambda_nm", Domain::wavelength_nm},
                       {u, "u", Domain::random_number, true}});
    auto wo = batch.output<double>(3);
    auto weight = batch.output<double>();
    auto pdf = batch.output<double>();
    auto delta = batch.output<bool>();
    double *w = wo.mutable_data(), *f = weight.mutable_data(), *p = pdf.mutable_data();
    bool* d = delta.mutable_data();
    batch.for_each([&](std::size_t i) {
        const double* r = batch.at(2, i);
        const auto s = model.sample(vec(batch.at(0, i)), *batch.at(1, i), r[0], Vec2(r[1], r[2]));
        const Vec3 v = s ? s->wo : Vec3(0, 0, 0);
        w[3 * i] = v.x;
        w[3 * i + 1] = v.y;
        w[3 * i + 2] = v.z;
        f[i] = s ? s->weight : 0.0;
        p[i] = s ? s->pdf : 0.0;
        d[i] = s && s->delta;
    });
    return py::make_tuple(wo, result(weight), result(pdf), result(delta));
}

py::tuple albedo(const bsdf::Bsdf& model, py::handle theta_i_deg, py::handle lambda_nm, py::handle phi_i_deg) {
    const Batch batch({{theta_i_deg, "theta_i_deg", Domain::incidence_deg}, {lambda_nm, "lambda_nm", Domain::wavelength_nm},
                       {phi_i_deg, "phi_i_deg", Domain::any}});
    auto total = batch.output<double>();
    auto specular = batch.output<double>();
    double *t = total.mutable_data(), *s = specular.mutable_data();
    batch.for_each([&](std::size_t i) {
        const auto a = bsdf::directional_albedo(model, *batch.at(0, i) * kDegree, *batch.at(1, i), *batch.at(2, i) * kDegree);
        t[i] = a.total();
        s[i] = a.specular;
    });
    return py::make_tuple(result(total), result(specular));
}

constexpr const char* kBsdfDoc = R"(Builds a scattering model (docs/MODELS.md) from its options.

model: 'ghs' (full GHS), 'ghs_ssa' (smooth-surface approximation), 'ggx_stats' (GGX from the surface statistics,
    or of a given alpha), 'two_scale': the scene plugins' names (docs/CONVENTIONS.md; old spellings such as 'ggx'
    work with a DeprecationWarning).
surface: the surface statistics: KCorrelation(sigma, corr_length, gamma), GaussianAcv(sigma, corr_length) (either
    elliptical with corr_length_v= and lay_angle_deg=: models ghs, ghs_ssa, ggx_stats and two_scale), a
    MapStatistics (measured_statistics(height_map): psd 'measured'), a heightmap::HeightMap or the path of a height map file
    (after removing `form`: KC fitted to it, or with psd='measured' its own radial PSD); or None and the XML's
    keywords psd ('kc' | 'gaussian' | 'file' | 'measured'), sigma (um), corr_length (um), gamma, corr_length_v (um),
    lay_angle_deg, surface_file.
material: 'perfect', a built-in metal (Au, Ag, Al, Cu, ...) or a refractive-index file (as Conductor).
Keyword options, named and spelled as in the XML plugins and bsdf::ModelOptions:
    method 'exact' | 'refit' (GHS lobe), truncation 'three_sigma' | 'poisson_mass', epsilon,
    fresnel 'incident' | 'half' | 'rr', renormalization True | False, ssa_form 'energy' | 'strict',
    alpha (ggx_stats; alone it means alpha_from 'none'), alpha_from 'measured' (default: the surface's rms slope)
    | 'smoothed' | 'kc_link' | 'none', smoothing (um),
    cutoff_wavelengths (two-scale N), macro_ndf 'ggx' | 'beckmann', form 'none' | 'plane' | 'poly2'..'poly4',
    psd_fit 'isotropic' (default) | 'elliptical' (a height map's KC fit: the elliptical one makes ghs, ghs_ssa and
    ggx_stats anisotropic, with the fitted LU, LV and lay angle; psd 'file' only),
    measured_spectrum '2d' (default with psd 'measured': ghs and ghs_ssa on the map's 2-D spectrum) | 'ring' (its
    ring average, as before).
Unknown options, bad values and missing parameters raise surfscatter.Error with the library's message.
Building a model may tabulate its lobes (seconds the first time; cached on disk, $SURFSCATTER_CACHE_DIR).

Units everywhere: wavelengths lambda_nm in nm, angles *_deg in degrees, lengths in um; directions wi (toward the
light) and wo (toward the viewer) are unit vectors (..., 3) in the local frame (z = normal) pointing away from the
surface; BRDF values in 1/sr without the cosine.)";

}  // namespace

void bind_bsdf(py::module_& m) {
    py::class_<PyBsdf>(m, "Bsdf",
                       "A scattering model built by surfscatter.bsdf(). eval, pdf, sample, albedo and the delta-lobe "
                       "figures are vectorised with numpy broadcasting and run in parallel (TBB) without the GIL.")
        .def_property_readonly("name", [](const PyBsdf& b) { return b.model->name(); }, "the model's name")
        .def_property_readonly("options", [](const PyBsdf& b) { return options_dict(b.options); },
                               "the options the model was built from (ModelOptions names)")
        .def_readonly("notes", &PyBsdf::notes,
                      "what the user should know about the model without it being an error (e.g. the range a "
                      "measured PSD covers and how it is extrapolated); each is also issued as a UserWarning")
        .def_property_readonly("is_pure_delta", [](const PyBsdf& b) { return b.model->is_pure_delta(); },
                               "True for a smooth mirror (no continuous part)")
        .def(
            "eval",
            [](const PyBsdf& b, py::handle wi, py::handle wo, py::handle lambda_nm) {
                // psd measured: the directions beyond the band the measurement resolves, counted as `brdf eval`
                // counts them, one UserWarning with the count (at the shortest wavelength among them).
                std::atomic<std::size_t> beyond{0}, total{0};
                std::atomic<double> shortest{std::numeric_limits<double>::infinity()};
                auto values = pair_map(wi, wo, lambda_nm, [&](const Vec3& i, const Vec3& o, double l) {
                    if (b.band) {
                        ++total;
                        if (b.band->beyond(i, o, l)) {
                            ++beyond;
                            for (double s = shortest.load(); l < s && !shortest.compare_exchange_weak(s, l);) {
                            }
                        }
                    }
                    return b.model->eval(i, o, l);
                });
                if (b.band && beyond > 0) warn(bsdf::beyond_band_warning(*b.band, beyond, total, shortest));
                return values;
            },
            py::arg("wi"), py::arg("wo"), py::arg("lambda_nm"),
            "f_r(wi, wo) in 1/sr (no cosine, no specular delta) for unit vectors wi, wo (..., 3) and wavelengths "
            "lambda_nm (nm), broadcast together; 0 where a direction is below the surface. As `brdf eval`; with "
            "psd 'measured', one UserWarning with the count of directions whose first-order frequency lies beyond "
            "the band the map resolves.")
        .def(
            "pdf",
            [](const PyBsdf& b, py::handle wi, py::handle wo, py::handle lambda_nm) {
                return pair_map(wi, wo, lambda_nm,
                                [&](const Vec3& i, const Vec3& o, double l) { return b.model->pdf(i, o, l); });
            },
            py::arg("wi"), py::arg("wo"), py::arg("lambda_nm"),
            "Solid-angle density (1/sr) with which sample() draws wo given wi, of its continuous part (including "
            "the factor 1 - delta_probability), broadcast over wi, wo (..., 3) and lambda_nm (nm).")
        .def(
            "sample", [](const PyBsdf& b, py::handle wi, py::handle lambda_nm, py::handle u) { return sample(*b.model, wi, lambda_nm, u); },
            py::arg("wi"), py::arg("lambda_nm"), py::arg("u"),
            "Draws outgoing directions: u (..., 3) holds uniform random numbers in [0, 1) (u[..., 0] picks the "
            "delta or the continuous lobe, u[..., 1:] drive the continuous sampler), broadcast with wi (..., 3) and "
            "lambda_nm (nm). Returns (wo (..., 3), weight, pdf, delta): weight = f cos(theta_o) / pdf for the "
            "continuous part and delta_reflectance / pdf for the delta lobe; pdf the solid-angle density or the "
            "delta lobe's probability; delta True where the delta lobe was chosen. Where no direction could be "
            "drawn (wi below the surface, a sample below the horizon) wo = 0, weight = 0, pdf = 0.")
        .def(
            "delta_reflectance",
            [](const PyBsdf& b, py::handle wi, py::handle lambda_nm) {
                return incident_map(wi, lambda_nm, [&](const Vec3& i, double l) { return b.model->delta_reflectance(i, l); });
            },
            py::arg("wi"), py::arg("lambda_nm"),
            "Reflectance carried by the specular delta lobe toward the mirror direction (0 if the model has none).")
        .def(
            "delta_probability",
            [](const PyBsdf& b, py::handle wi, py::handle lambda_nm) {
                return incident_map(wi, lambda_nm, [&](const Vec3& i, double l) { return b.model->delta_probability(i, l); });
            },
            py::arg("wi"), py::arg("lambda_nm"), "Probability that sample() chooses the delta lobe.")
        .def(
            "albedo",
            [](const PyBsdf& b, py::handle theta_i_deg, py::handle lambda_nm, py::handle phi_i_deg) {
                return albedo(*b.model, theta_i_deg, lambda_nm, phi_i_deg);
            },
            py::arg("theta_i_deg"), py::arg("lambda_nm"), py::arg("phi_i_deg") = 0.0,
            "Directional albedo at incidence theta_i_deg in [0, 90) degrees, azimuth phi_i_deg (matters for an "
            "elliptical surface only) and wavelength lambda_nm (nm), "
            "broadcast: (total, specular), total = integral of f cos(theta_o) over the hemisphere plus the delta "
            "lobe, specular = the delta lobe alone. As `brdf albedo`.")
        .def("__repr__", [](const PyBsdf& b) {
            const auto& s = b.options.surface;
            return fmt::format("<surfscatter.Bsdf {} material={} psd={}{}>", b.model->name(), b.options.material,
                               to_string(s.psd),
                               b.model->isotropic()                  ? ""
                               : s.psd_fit == bsdf::PsdFit::elliptical ? std::string(" psd_fit=elliptical")
                                                                       : fmt::format(" corr_length={} corr_length_v={} lay_angle_deg={}",
                                                                                     s.corr_length, s.corr_length_v, s.lay_angle));
        });

    m.def("bsdf", &make, py::arg("model") = "ghs", py::arg("surface") = py::none(), py::arg("material") = "perfect",
          kBsdfDoc);

    m.def(
        "export_rgl",
        [](const PyBsdf& b, const std::string& path, const std::string& format, int theta_i_count,
           std::optional<int> phi_i_count, int sample_resolution, int ndf_resolution,
           std::optional<double> lambda_step_nm, double tolerance_percent, std::optional<double> specular_lobe_deg) {
            if (format != "rgl-spectral" && format != "rgl-rgb")
                fail("format must be one of rgl-spectral | rgl-rgb, got '{}'", printable(format));
            // None is "not given", as an option the CLI is not given: one that does not apply is an error.
            if (b.model->isotropic() && phi_i_count) fail("phi_i_count applies to anisotropic surfaces only");
            if (format == "rgl-rgb" && lambda_step_nm) fail("lambda_step_nm applies to format rgl-spectral only");
            bsdf::RglExportOptions o;
            o.names = {"theta_i_count", "phi_i_count", "ndf_resolution", "sample_resolution", "lambda_step_nm"};
            o.rgb = format == "rgl-rgb";
            o.theta_i_count = theta_i_count, o.phi_i_count = phi_i_count.value_or(o.phi_i_count);
            o.sample_resolution = sample_resolution, o.ndf_resolution = ndf_resolution;
            o.lambda_step_nm = lambda_step_nm.value_or(o.lambda_step_nm);
            o.tolerance_percent = tolerance_percent;
            bsdf::check_rgl_accuracy({}, tolerance_percent, "tolerance_percent", path);
            std::optional<bsdf::SpecularAsLobe> with_lobe;
            if (specular_lobe_deg) with_lobe.emplace(*b.model, *specular_lobe_deg * kDegree, "specular_lobe_deg");
            if (with_lobe) o.mirror_exclusion_rad = with_lobe->core_rad();
            const bsdf::Bsdf& tabulated = with_lobe ? static_cast<const bsdf::Bsdf&>(*with_lobe) : *b.model;
            bsdf::RglAccuracy acc;
            {
                py::gil_scoped_release release;
                bsdf::write_rgl(path, bsdf::export_rgl(tabulated, o, fmt::format("surfscatter {} export ({})",
                                                                                b.model->name(), format)));
                acc = bsdf::rgl_file_accuracy(tabulated, path, o);
            }
            bsdf::check_rgl_accuracy(acc, tolerance_percent, "tolerance_percent", path);
            return py::dict("worst"_a = acc.worst, "rms"_a = acc.rms, "compared"_a = acc.compared,
                            "theta_i_deg"_a = acc.theta_i_deg, "phi_i_deg"_a = acc.phi_i_deg,
                            "theta_o_deg"_a = acc.theta_o_deg, "phi_o_deg"_a = acc.phi_o_deg,
                            "lambda_nm"_a = acc.lambda_nm, "jump_band"_a = acc.jump_band,
                            "jump_worst"_a = acc.jump_worst, "jump_compared"_a = acc.jump_compared);
        },
        py::arg("model"), py::arg("path"), py::arg("format") = "rgl-spectral", py::arg("theta_i_count") = 16,
        py::arg("phi_i_count") = py::none(), py::arg("sample_resolution") = 64, py::arg("ndf_resolution") = 128,
        py::arg("lambda_step_nm") = py::none(), py::arg("tolerance_percent") = 2.0, py::arg("specular_lobe_deg") = py::none(),
        "Writes the model's continuous part as an RGL measured BSDF file (Mitsuba 3 / pbrt-v4 `measured`), as "
        "`surfscatter brdf export`: format 'rgl-spectral' (360-1000 nm, every lambda_step_nm, default 3.2) or "
        "'rgl-rgb'; phi_i_count incidence azimuths for an anisotropic model (default 17; an error for an isotropic "
        "one); the coherent specular part is "
        "not in the file (model.delta_reflectance gives it) unless specular_lobe_deg carries it as a narrow lobe of that "
        "width (docs/RENDERER.md). Returns the written file's accuracy "
        "against the model (dict: worst and rms relative error where f >= 1 % of its peak and theta_o <= 80 deg, "
        "directions compared, where the worst is; lambda_nm 0 for rgb files, compared in CIE Y; for a model whose "
        "lobe jumps, two_scale, jump_band, jump_worst and jump_compared: the directions within jump_band (relative) "
        "of the jump's radius, compared apart and left out of worst; docs/MODELS.md); raises Error after "
        "writing when the worst exceeds tolerance_percent.");

    m.def(
        "read_rgl",
        [](const std::string& path) {
            io::TensorFile file = io::read_tensor_file(path);
            bsdf::rgl_from_tensor(file, path);  // checks the fields as a reader of the format does
            py::dict out;
            for (const auto& f : file.fields) {
                if (f.name == "description") {
                    out["description"] = py::str(f.bytes);
                    continue;
                }
                std::vector<py::ssize_t> shape(f.shape.begin(), f.shape.end());
                py::dtype dtype;
                switch (f.dtype) {
                    case io::TensorDtype::UInt8: dtype = py::dtype::of<std::uint8_t>(); break;
                    case io::TensorDtype::UInt32: dtype = py::dtype::of<std::uint32_t>(); break;
                    case io::TensorDtype::Float32: dtype = py::dtype::of<float>(); break;
                    default: {
                        const auto values = f.values();
                        py::array_t<double> a(shape);
                        std::copy(values.begin(), values.end(), a.mutable_data());
                        out[py::str(f.name)] = a;
                        continue;
                    }
                }
                py::array a(dtype, shape);
                std::memcpy(a.mutable_data(), f.bytes.data(), f.bytes.size());
                out[py::str(f.name)] = a;
            }
            return out;
        },
        py::arg("path"),
        "The fields of an RGL measured BSDF file (checked as Mitsuba 3's reader checks them) as a dict of numpy "
        "arrays in the file's dtypes and shapes (theta_i, phi_i in radians; ndf, sigma, vndf, luminance, rgb or "
        "wavelengths (nm) + spectra, jacobian, valid, version) and 'description' as a str.");
}

}  // namespace surfscatter::python
