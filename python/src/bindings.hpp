#pragma once
// One function per library module adds its classes and functions to the extension module (module.cpp).
#include <pybind11/pybind11.h>

namespace surfscatter::python {

void bind_core(pybind11::module_& m);
void bind_material(pybind11::module_& m);
void bind_surface(pybind11::module_& m);
void bind_bsdf(pybind11::module_& m);
void bind_profile_lobes(pybind11::module_& m);
void bind_render(pybind11::module_& m);
void bind_photo(pybind11::module_& m);

}  // namespace surfscatter::python
