// surfscatter.validity: which model to trust for a surface (validity/validity.hpp), as `surfscatter validity`.
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/validity/validity.hpp"

namespace surfscatter::python {

namespace {

py::dict validity(const surface::RadialStatistics& surface, const std::string& material,
                  const std::vector<double>& wavelengths_nm, const std::vector<double>& theta_i_deg,
                  double length_um, double beam_width_um, std::size_t realizations,
                  const std::vector<std::string>& polarisations, std::uint64_t seed, double bin_deg,
                  double tolerance, double max_reference_stderr, int threads) {
    const auto conductor = material::Conductor::from_name(material);
    validity::ProfileStudy study;
    study.wavelengths_nm = wavelengths_nm;
    study.theta_i_deg = theta_i_deg;
    for (const auto& p : polarisations)
        study.polarisations.push_back(bsdf::parse_profile_polarisation(p, "polarisations"));
    study.beam_width_um = beam_width_um;
    study.statistical.length_um = length_um;
    study.statistical.realizations = realizations;
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
    for (const auto& row : validity::table(cases)) {
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
        rows.append(d);
    }
    py::list verdicts;
    for (const auto& c : cases) {
        py::dict v;
        v["wavelength_nm"] = c.wavelength_nm;
        v["theta_i_deg"] = c.theta_i_deg;
        v["polarisation"] = validity::to_string(c.polarisation);
        v["conclusive"] = c.verdict.conclusive;
        v["trusted"] = c.verdict.trusted;
        v["best_model"] = c.verdict.best_model;
        v["within_tolerance"] = c.verdict.within_tolerance;
        v["ruled_out"] = c.verdict.ruled_out;
        v["text"] = c.verdict.text;
        verdicts.append(v);
    }
    py::dict out;
    out["table"] = rows;
    out["verdicts"] = verdicts;
    return out;
}

}  // namespace

void bind_validity(py::module_& m) {
    m.def("validity", &validity, py::arg("surface"), py::arg("material"), py::arg("wavelengths_nm"),
          py::arg("theta_i_deg"), py::arg("length_um"), py::arg("beam_width_um"), py::arg("realizations"),
          py::arg("polarisations") = std::vector<std::string>{"s", "p"}, py::arg("seed") = 1,
          py::arg("bin_deg") = 3.0, py::arg("tolerance") = 0.1, py::arg("max_reference_stderr") = 0.25,
          py::arg("threads") = 0,
          R"(Which model to trust for profiles cut through `surface` (KCorrelation or GaussianAcv), as `surfscatter
validity` (docs/VALIDITY.md): the 1-D GHS, SSA and Kirchhoff forms against exact-1d averaged over `realizations`
random profiles of length_um (Thorsos beam of width beam_width_um), for every wavelength in wavelengths_nm (nm),
incidence in theta_i_deg (degrees) and polarisation ('s', 'p'). Returns {'table': one dict per model and case with
the CSV's columns, 'verdicts': one dict per case (conclusive, trusted, best_model, within_tolerance, ruled_out, text)}.)");
}

}  // namespace surfscatter::python
