// surfscatter.profile_models: the 1-D forms of GHS, SSA and Kirchhoff (bsdf/profile_lobes.hpp), as
// `surfscatter reference models-1d` writes them.
#include <string>
#include <vector>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::python {

namespace {

py::dict profile_models(const surface::RadialStatistics& surface, const std::string& material, double wavelength_nm,
                        double theta_i_deg, const std::string& polarisation, py::object theta_o_deg,
                        const std::vector<std::string>& models, py::object fresnel, py::object renormalization,
                        py::object ssa_form) {
    const auto conductor = material::Conductor::from_name(material);
    const auto pol = bsdf::parse_profile_polarisation(polarisation, "polarisation");
    bsdf::ProfileModelOptions options;
    if (!fresnel.is_none()) options.fresnel = bsdf::parse_fresnel(text_option(fresnel, "fresnel"), "fresnel");
    if (!ssa_form.is_none()) options.ssa_form = bsdf::parse_ssa_form(text_option(ssa_form, "ssa_form"), "ssa_form");
    if (!renormalization.is_none()) options.renormalization = bool_option(renormalization, "renormalization");
    std::vector<bsdf::ProfileModel> kinds;
    for (const auto& name : models) kinds.push_back(bsdf::parse_profile_model(name, "models"));
    if (kinds.empty()) fail("models must name at least one of ghs | ghs_ssa | kirchhoff");
    // An option none of the models uses is an error, as at the CLI.
    for (const auto& [given, option] : {std::pair{!fresnel.is_none(), "fresnel"}, std::pair{!ssa_form.is_none(), "ssa_form"},
                                        std::pair{!renormalization.is_none(), "renormalization"}}) {
        const auto why = bsdf::inapplicable_profile_option(kinds, option);
        if (given && !why.empty()) fail("{} is {}", option, why);
    }
    std::vector<double> theta_o;
    if (theta_o_deg.is_none()) theta_o = bsdf::uniform_theta_grid(reference::kFarFieldSteps);
    else {
        const RealArray degrees = real_array(theta_o_deg, "theta_o_deg");
        for (py::ssize_t j = 0; j < degrees.size(); ++j) theta_o.push_back(degrees.data()[j] * kDegree);
    }
    bsdf::require_profile_wavelength(wavelength_nm, "wavelength_nm");
    std::vector<bsdf::ProfileLobe> lobes;
    {
        const py::gil_scoped_release release;
        for (const auto kind : kinds) {
            options.model = kind;
            lobes.push_back(bsdf::profile_lobe(surface, conductor, wavelength_nm, theta_i_deg * kDegree, pol, options,
                                               theta_o));
        }
    }
    py::dict out;
    std::vector<double> degrees;
    for (const double t : theta_o) degrees.push_back(t / kDegree);
    out["theta_o_deg"] = to_array(degrees);
    for (std::size_t m = 0; m < kinds.size(); ++m) {
        py::dict lobe;
        lobe["intensity_per_rad"] = to_array(lobes[m].intensity_per_rad);
        lobe["coherent"] = lobes[m].coherent;
        lobe["sigma_um"] = lobes[m].sigma_um;
        lobe["normalization"] = lobes[m].normalization;
        out[py::str(bsdf::to_string(kinds[m]))] = lobe;
    }
    return out;
}

}  // namespace

void bind_profile_lobes(py::module_& m) {
    m.def("profile_models", &profile_models, py::arg("surface"), py::arg("material"), py::arg("wavelength_nm"),
          py::arg("theta_i_deg"), py::arg("polarisation"), py::arg("theta_o_deg") = py::none(),
          py::arg("models") = std::vector<std::string>{"ghs", "ghs_ssa", "kirchhoff"},
          py::arg("fresnel") = py::none(), py::arg("renormalization") = py::none(), py::arg("ssa_form") = py::none(),
          R"(The 1-D forms of GHS, SSA and Kirchhoff for a profile cut through `surface` (KCorrelation or GaussianAcv),
as `surfscatter reference models-1d` (docs/MODELS.md "One-dimensional forms"): light in the x-z plane arriving from
negative x, specular at theta_o = +theta_i_deg (degrees, [0, 90)), wavelength_nm in nm, polarisation 's' or 'p',
material 'perfect', a built-in metal or a refractive-index file. theta_o_deg: the outgoing angles in degrees
(default -90, -89.9, ..., 90, exact-1d's grid). models: any of 'ghs', 'ghs_ssa', 'kirchhoff'. fresnel ('incident' |
'half' | 'rr', ghs and ghs_ssa), renormalization (ghs), ssa_form ('energy' | 'strict', ghs_ssa): as the CLI options;
one no chosen model uses raises surfscatter.Error. Returns {'theta_o_deg': array, name: {'intensity_per_rad': the
incoherent part per radian over the incident power, 'coherent': the specular fraction, 'sigma_um': the sigma in g,
'normalization': K}} per model.)");
}

}  // namespace surfscatter::python
