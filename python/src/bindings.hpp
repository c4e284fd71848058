#pragma once
// One function per library module adds its classes and functions to the extension module (module.cpp).
#include <pybind11/pybind11.h>

namespace surfscatter::python {

void bind_core(pybind11::module_& m);
void bind_material(pybind11::module_& m);
void bind_surface(pybind11::module_& m);
void bind_bsdf(pybind11::module_& m);
void bind_profile_lobes(pybind11::module_& m);
void bind_validity(pybind11::module_& m);
void bind_inverse(pybind11::module_& m);
void bind_render(pybind11::module_& m);
void bind_photo(pybind11::module_& m);

// The lay of a KCorrelation or GaussianAcv made with corr_length_v / lay_angle_deg (bind_surface.cpp): corr_length_v
// 0 where not given (LV = corr_length), lay_angle_deg 0 by default.
struct Lay {
    double corr_length_v = 0, lay_angle_deg = 0;
};
Lay lay_of(pybind11::handle statistics);

}  // namespace surfscatter::python
