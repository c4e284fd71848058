// surfscatter.Conductor: material/conductor.hpp.
#include <complex>

#include <pybind11/complex.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"

namespace surfscatter::python {

void bind_material(py::module_& m) {
    using material::Conductor;
    py::class_<Conductor>(m, "Conductor",
                          "A metal as the scattering models see it: a complex refractive index N = n + ik over "
                          "wavelength, or the perfect conductor (R = 1 everywhere). docs/MATERIALS.md.")
        .def(py::init([](py::handle name) { return Conductor::from_name(path_string(name, "material")); }),
             py::arg("material"),
             "material: 'perfect', a built-in metal (Ag Al Au Be Cr Cu Ni Pd Pt Ti W: Lorentz-Drude fits of Rakic "
             "1998), or the path of a refractiveindex.info .yml or a wavelength_nm,n,k .csv file (as --material).")
        .def_property_readonly("name", &Conductor::name, "The name or file the conductor was made from.")
        .def_property_readonly("is_perfect", &Conductor::is_perfect, "True for the perfect conductor.")
        .def(
            "ior",
            [](const Conductor& c, py::handle lambda_nm) {
                if (c.is_perfect()) fail("the perfect conductor has no finite refractive index");
                const Batch batch({{lambda_nm, "lambda_nm", Domain::wavelength_nm}});
                auto out = batch.output<std::complex<double>>();
                std::complex<double>* values = out.mutable_data();
                batch.for_each([&](std::size_t i) { values[i] = c.ior(*batch.at(0, i)); });
                return result(out);
            },
            py::arg("lambda_nm"),
            "Complex refractive index n + ik (complex128, same shape as lambda_nm) at wavelengths lambda_nm (nm). "
            "Error outside the data's wavelength range, and for the perfect conductor.")
        .def(
            "reflectance",
            [](const Conductor& c, py::handle cos_theta, py::handle lambda_nm, const std::string& polarization) {
                if (polarization != "unpolarized" && polarization != "s" && polarization != "p")
                    fail("polarization must be s, p or unpolarized, got '{}'", polarization);
                const char pol = polarization[0];
                return map_scalars({{cos_theta, "cos_theta", Domain::unit_interval},
                                    {lambda_nm, "lambda_nm", Domain::wavelength_nm}},
                                   [&](double cos_t, double lambda) {
                                       const auto r = c.reflectance_sp(cos_t, lambda);
                                       return pol == 's' ? r.rs : pol == 'p' ? r.rp : r.unpolarized();
                                   });
            },
            py::arg("cos_theta"), py::arg("lambda_nm"), py::arg("polarization") = "unpolarized",
            "Exact Fresnel reflectance (complex Snell, never Schlick) at incidence cosine cos_theta in [0, 1] and "
            "wavelength lambda_nm (nm), broadcast together; polarization 's', 'p' or 'unpolarized' (their mean). "
            "As `surfscatter fresnel`.")
        .def("__repr__", [](const Conductor& c) { return "surfscatter.Conductor('" + c.name() + "')"; });
}

}  // namespace surfscatter::python
