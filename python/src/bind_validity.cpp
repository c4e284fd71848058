// surfscatter.validity: which model to trust for a surface (validity/validity.hpp), as `surfscatter validity`.
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/validity/map_validity.hpp"
#include "surfscatter/validity/validity.hpp"

namespace surfscatter::python {

using namespace pybind11::literals;

namespace {

// How the library's checks and remedies name validity's arguments (points per wavelength: fixed at 10 here).
const reference::OptionNames kOptionNames = {.length = "length_um",
                                             .wavelength = "wavelengths_nm",
                                             .points_per_wavelength = "",
                                             .threads = "threads",
                                             .beam_width = "beam_width_um",
                                             .material = "material",
                                             .realizations = "realizations",
                                             .tolerance = "tolerance",
                                             .bin_deg = "bin_deg",
                                             .max_reference_stderr = "max_reference_stderr",
                                             .subarea = "subarea_um"};

py::dict row_dict(const validity::TableRow& row) {
    py::dict d;
    d["model"] = row.model;
    d["wavelength_nm"] = row.wavelength_nm;
    d["theta_i_deg"] = row.theta_i_deg;
    d["polarisation"] = row.polarisation;
    d["median_rel_error"] = row.comparison.median_rel_error;
    d["worst_rel_error"] = row.comparison.worst_rel_error;
    d["worst_theta_o_deg"] = row.comparison.worst_theta_o_rad / kDegree;
    d["directions_used"] = row.comparison.directions_used;
    d["directions_excluded"] = row.comparison.directions_excluded;
    d["reference_median_rel_stderr"] = row.comparison.reference_median_rel_stderr;
    d["model_energy"] = row.model_energy;
    d["reference_energy"] = row.reference_energy;
    d["trusted"] = row.trusted;
    d["verdict"] = row.verdict;
    return d;
}

py::dict verdict_dict(const validity::Verdict& verdict) {
    py::dict v;
    v["conclusive"] = verdict.conclusive;
    v["trusted"] = verdict.trusted;
    v["best_model"] = verdict.best_model;
    v["indistinguishable"] = verdict.indistinguishable;
    v["within_tolerance"] = verdict.within_tolerance;
    v["ruled_out"] = verdict.ruled_out;
    v["reference_problem"] = verdict.reference_problem;
    v["text"] = verdict.text;
    return v;
}

py::dict validity(py::handle surface_arg, const std::string& material,
                  const std::vector<double>& wavelengths_nm, const std::vector<double>& theta_i_deg,
                  double length_um, double beam_width_um, const py::object& realizations,
                  const std::vector<std::string>& polarisations, std::uint64_t seed, double bin_deg,
                  double tolerance, double max_reference_stderr, int threads, const py::object& target_stderr_pct,
                  const py::object& max_realizations_arg) {
    if (!realizations.is_none() && !target_stderr_pct.is_none())
        fail("realizations and target_stderr_pct: give one (a fixed count of profiles, or profiles until the "
             "reference's standard error reaches the target)");
    const double target = realizations.is_none()
                              ? (target_stderr_pct.is_none() ? 2.0 : real_scalar(target_stderr_pct, "target_stderr_pct"))
                              : 0.0;
    if (realizations.is_none() && !(target > 0 && target < 100))
        fail("target_stderr_pct must be in (0, 100) percent, got {}", target);
    if (!realizations.is_none() && !max_realizations_arg.is_none())
        fail("max_realizations caps target_stderr_pct's profiles; realizations is a fixed count");
    const long long max_realizations =
        max_realizations_arg.is_none() ? 1000 : integer_option(max_realizations_arg, "max_realizations", std::numeric_limits<long long>::min());
    if (realizations.is_none() && !(max_realizations >= 2 && max_realizations <= 1000000))
        fail("max_realizations must be in [2, 1000000], got {}", max_realizations);
    if (!py::isinstance<surface::KCorrelation>(surface_arg) && !py::isinstance<surface::GaussianAcv>(surface_arg))
        fail("surface must be a KCorrelation or a GaussianAcv, got {}", py::repr(surface_arg).cast<std::string>());
    const auto& surface = surface_arg.cast<const surface::RadialStatistics&>();
    // The profiles are cuts through isotropic statistics (as the CLI's profiles route): an elliptical surface's
    // lay would be dropped.
    const Lay lay = lay_of(surface_arg);
    if (lay.corr_length_v != 0 || lay.lay_angle_deg != 0)
        fail("validity: surface is elliptical (corr_length_v {}, lay_angle_deg {}) and the profiles are cuts through "
             "isotropic statistics: validity_map takes elliptical statistics", lay.corr_length_v, lay.lay_angle_deg);
    const auto conductor = material::Conductor::from_name(material);
    validity::ProfileStudy study;
    study.wavelengths_nm = wavelengths_nm;
    study.theta_i_deg = theta_i_deg;
    for (const auto& p : polarisations)
        study.polarisations.push_back(bsdf::parse_profile_polarisation(p, "polarisations"));
    study.beam_width_um = beam_width_um;
    study.option_names = kOptionNames;
    study.statistical.length_um = length_um;
    study.statistical.realizations = realizations.is_none() ? static_cast<std::size_t>(max_realizations)
                                                            : static_cast<std::size_t>(integer_option(realizations, "realizations", 2));
    study.target_rel_stderr = target / 100;
    study.statistical.seed = seed;
    study.statistical.threads = threads;
    study.criteria.bin_deg = bin_deg;
    study.criteria.tolerance = tolerance;
    study.criteria.max_reference_stderr = max_reference_stderr;
    std::vector<validity::ProfileCase> cases;
    {
        const py::gil_scoped_release release;
        cases = validity::profile_validity(surface, conductor, study);
    }
    py::list rows;
    for (const auto& row : validity::table(cases)) rows.append(row_dict(row));
    py::list verdicts;
    for (const auto& c : cases) {
        py::dict v = verdict_dict(c.verdict);
        v["wavelength_nm"] = c.wavelength_nm;
        v["theta_i_deg"] = c.theta_i_deg;
        v["polarisation"] = validity::to_string(c.polarisation);
        v["realizations"] = c.reference.realizations;
        v["reference_median_rel_stderr"] = c.reference_rel_stderr;
        v["target_reached"] = c.target_reached;
        v["render_verdict"] = verdict_dict(c.render_verdict);
        v["not_compared"] = c.not_compared;
        verdicts.append(v);
    }
    py::dict out;
    out["table"] = rows;
    out["verdicts"] = verdicts;
    return out;
}

// surface=: KC / Gaussian statistics (with their lay) to synthesise maps from, or a height map (object or path).
bsdf::SurfaceOptions map_surface_options(py::handle surface, const heightmap::Preparation& preparation) {
    bsdf::SurfaceOptions s;
    s.preparation = preparation;
    if (py::isinstance<surface::KCorrelation>(surface) || py::isinstance<surface::GaussianAcv>(surface)) {
        const auto& radial = surface.cast<const surface::RadialStatistics&>();
        s.psd = py::isinstance<surface::KCorrelation>(surface) ? bsdf::PsdKind::kc : bsdf::PsdKind::gaussian;
        s.sigma = radial.sigma_h();
        s.corr_length = radial.correlation_length();
        if (s.psd == bsdf::PsdKind::kc) s.gamma = surface.cast<const surface::KCorrelation&>().gamma();
        const Lay lay = lay_of(surface);
        s.corr_length_v = lay.corr_length_v;
        s.lay_angle = lay.lay_angle_deg;
        return s;
    }
    s.psd = bsdf::PsdKind::measured;
    if (py::isinstance<heightmap::HeightMap>(surface)) {
        const auto map = surface.cast<std::shared_ptr<heightmap::HeightMap>>();
        s.surface_file = map->origin();
        s.height_map = map;
    } else if (py::isinstance<py::str>(surface) ||
               py::isinstance(surface, py::module_::import("os").attr("PathLike"))) {
        s.surface_file = py::str(surface).cast<std::string>();
    } else {
        fail("surface must be a KCorrelation, a GaussianAcv, a HeightMap or the path of a height map file, got {}",
             py::repr(surface).cast<std::string>());
    }
    return s;
}

py::dict validity_map(py::handle surface_arg, const std::string& material, const std::vector<double>& wavelengths_nm,
                      const std::vector<double>& theta_i_deg, const std::vector<double>& phi_i_deg,
                      const py::object& form, const py::object& outliers, const py::object& row_alignment,
                      const py::object& lambda_s_um, const py::object& lambda_c_um, std::optional<double> map_size_um,
                      std::optional<long long> map_pixels, std::optional<long long> realizations,
                      std::optional<std::uint64_t> seed, double subarea_um,
                      double max_theta_o_deg, double bin_deg, double tolerance, double max_reference_stderr,
                      int threads) {
    // None is "not given", as an option the CLI is not given: an argument the surface's route does not use is an
    // error even at its default value.
    const auto text_or = [](const py::object& value, const char* name, const char* fallback) {
        return value.is_none() ? std::string(fallback) : text_option(value, name);
    };
    const heightmap::Preparation preparation = preparation_arguments(
        text_or(outliers, "outliers", "keep"), text_or(row_alignment, "row_alignment", "auto"),
        text_or(form, "form", "plane"), lambda_s_um.is_none() ? py::str("none") : lambda_s_um,
        lambda_c_um.is_none() ? py::str("auto") : lambda_c_um);
    const bsdf::SurfaceOptions options = map_surface_options(surface_arg, preparation);
    const bool measured = options.psd == bsdf::PsdKind::measured;
    const std::vector<std::pair<const char*, bool>> preparing = {
        {"outliers", !outliers.is_none()}, {"row_alignment", !row_alignment.is_none()}, {"form", !form.is_none()},
        {"lambda_s_um", !lambda_s_um.is_none()}, {"lambda_c_um", !lambda_c_um.is_none()}};
    const std::vector<std::pair<const char*, bool>> synthesising = {
        {"map_size_um", map_size_um.has_value()}, {"map_pixels", map_pixels.has_value()},
        {"realizations", realizations.has_value()}, {"seed", seed.has_value()}};
    for (const auto& [name, given] : measured ? synthesising : preparing) {
        if (!given) continue;
        if (measured)
            fail("{} synthesises maps from statistics (a KCorrelation or GaussianAcv): a height map is one realization", name);
        fail("{} prepares a measured map (a HeightMap or a file): maps synthesised from statistics take none of "
             "outliers, row_alignment, form, lambda_s_um and lambda_c_um", name);
    }
    if (!measured && !map_size_um) fail("map_size_um: give the side (um) of the maps synthesised from statistics");
    if (!measured) surface::require_surface_length(*map_size_um, "map_size_um");
    if (!measured) validity::require_synthesis_counts(map_pixels.value_or(256), realizations.value_or(1), "map_pixels", "realizations");
    if (!(max_theta_o_deg > 0 && max_theta_o_deg < 90))
        fail("max_theta_o_deg must be in (0, 90) degrees, got {}", max_theta_o_deg);
    if (subarea_um != 0) require_positive(subarea_um, "subarea_um");
    const auto conductor = material::Conductor::from_name(material);
    validity::MapStudy study;
    study.wavelengths_nm = wavelengths_nm;
    study.theta_i_deg = theta_i_deg;
    study.phi_i_deg = phi_i_deg;
    study.subarea_um = subarea_um;
    study.max_theta_o_deg = max_theta_o_deg;
    study.criteria.bin_deg = bin_deg;
    study.criteria.tolerance = tolerance;
    study.criteria.max_reference_stderr = max_reference_stderr;
    study.threads = threads;
    study.option_names = kOptionNames;
    if (measured) study.option_names.realizations.clear();  // one map
    validity::require_valid_criteria(study.criteria, kOptionNames);  // before the maps are made
    std::vector<validity::MapCase> cases;
    validity::MapSurface surface;
    {
        const py::gil_scoped_release release;
        surface = validity::map_surface(options, material,
                                        {map_size_um.value_or(0.0), static_cast<std::size_t>(map_pixels.value_or(256)),
                                         static_cast<std::size_t>(realizations.value_or(1)), seed.value_or(1)});
        cases = validity::map_validity(surface, conductor, study);
    }
    validity::require_outliers_not_dominant(surface);
    py::list rows;
    for (const auto& row : validity::table(cases)) {
        py::dict d = row_dict(row);
        d["phi_i_deg"] = row.phi_i_deg;
        d["reference_valid"] = row.reference_valid;
        rows.append(d);
    }
    py::list verdicts;
    for (const auto& c : cases) {
        py::dict v = verdict_dict(c.verdict);
        v["wavelength_nm"] = c.wavelength_nm;
        v["theta_i_deg"] = c.theta_i_deg;
        v["phi_i_deg"] = c.phi_i_deg;
        const auto& k = c.reference_validity;
        v["reference_validity"] = py::dict("valid"_a = k.valid, "k_l"_a = k.k_l, "curvature_share"_a = k.curvature_share,
                                           "median_radius_um"_a = k.median_radius_um,
                                           "shadowed_share"_a = k.shadowed_share, "text"_a = k.text);
        v["reference_energy"] = c.reference_energy;
        verdicts.append(v);
    }
    py::dict out;
    out["table"] = rows;
    out["verdicts"] = verdicts;
    out["refused_models"] = surface.refused;
    out["surface"] = surface.description;
    if (measured)
        out["outliers"] = py::dict("policy"_a = heightmap::to_string(surface.outlier_policy),
                                   "points"_a = surface.outliers.count, "share"_a = surface.outliers.share,
                                   "text"_a = heightmap::describe(surface.outliers));
    return out;
}

}  // namespace

void bind_validity(py::module_& m) {
    m.def("validity", &validity, py::arg("surface"), py::arg("material"), py::arg("wavelengths_nm"),
          py::arg("theta_i_deg"), py::arg("length_um"), py::arg("beam_width_um"), py::arg("realizations") = py::none(),
          py::arg("polarisations") = std::vector<std::string>{"s", "p"}, py::arg("seed") = 1,
          py::arg("bin_deg") = 3.0, py::arg("tolerance") = 0.1, py::arg("max_reference_stderr") = 0.25,
          py::arg("threads") = 0, py::arg("target_stderr_pct") = py::none(), py::arg("max_realizations") = py::none(),
          R"(Which model to trust for profiles cut through `surface` (KCorrelation or GaussianAcv), as `surfscatter
validity` (docs/VALIDITY.md): the 1-D GHS, SSA, Kirchhoff, GGX-from-statistics and two_scale forms against
exact-1d averaged over random profiles
of length_um (Thorsos beam of width beam_width_um): a fixed number `realizations`, or (the default) as many as bring
the reference's median relative standard error over the bins used to target_stderr_pct percent (default 2), at
most max_realizations (default 1000; verdicts' target_reached says whether it did); not both. For every wavelength in wavelengths_nm (nm),
incidence in theta_i_deg (degrees) and polarisation ('s', 'p'). Returns {'table': one dict per model and case with
the CSV's columns, 'verdicts': one dict per case (conclusive, trusted, best_model, indistinguishable, within_tolerance, ruled_out,
reference_problem, text, realizations, reference_median_rel_stderr, target_reached, render_verdict: the same
over the models a renderer offers (all but kirchhoff), not_compared: why a model is left out)}.)");
    m.def("validity_map", &validity_map, py::arg("surface"), py::arg("material"), py::arg("wavelengths_nm"),
          py::arg("theta_i_deg"), py::arg("phi_i_deg") = std::vector<double>{0.0}, py::arg("form") = py::none(),
          py::arg("outliers") = py::none(), py::arg("row_alignment") = py::none(), py::arg("lambda_s_um") = py::none(),
          py::arg("lambda_c_um") = py::none(), py::arg("map_size_um") = py::none(), py::arg("map_pixels") = py::none(),
          py::arg("realizations") = py::none(),
          py::arg("seed") = py::none(), py::arg("subarea_um") = 0.0, py::arg("max_theta_o_deg") = 80.0,
          py::arg("bin_deg") = 3.0, py::arg("tolerance") = 0.1, py::arg("max_reference_stderr") = 0.25,
          py::arg("threads") = 0,
          R"(Which 2-D model to trust for a height map, as `surfscatter validity --surface-file` / `--map-size-um`
(docs/VALIDITY.md, "Height maps"): every model the factory makes for `surface` against the Kirchhoff BRDF of the
map(s), with Kirchhoff's own validity. `surface`: a HeightMap or a height map path, prepared as outliers ('keep' or
'fill', an Error when kept ones dominate; default 'keep'), row_alignment ('auto'), form ('plane'), lambda_s_um
('none') and lambda_c_um ('auto') say (docs/HEIGHTMAPS.md
"Preparation"; the models from psd measured and psd file), or a KCorrelation / GaussianAcv, elliptical if made with corr_length_v /
lay_angle_deg (`realizations` (default 1) square maps of map_size_um and map_pixels (default 256) a side are
synthesised, seeds seed, seed + 1, ... (default 1)). An argument of the other kind of surface is an Error, even
at its default value. Wavelengths in nm, angles in degrees, subarea_um 0: a quarter of the map. Returns {'table': one dict per
model and case with the CSV's columns, 'verdicts': one dict per case (the verdict, its reference_validity and
reference_energy), 'refused_models': the models the factory does not make for this surface and why, 'surface',
'outliers' for a measured map (policy, points, share, text)}.)");
}

}  // namespace surfscatter::python
