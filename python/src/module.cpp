// The compiled part of the `surfscatter` Python package (python/surfscatter/__init__.py re-exports it).
#include <memory>
#include <mutex>

#include <fmt/format.h>
#include <pybind11/pybind11.h>
#include <tbb/global_control.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/deprecation.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::python {

namespace {

std::mutex thread_limit_mutex;
// Never destroyed: at interpreter exit TBB may be torn down before static destructors would run.
auto* const thread_limit = new std::unique_ptr<tbb::global_control>();

void set_max_threads(long long threads) {
    require_thread_count(threads, "threads");
    const std::lock_guard lock(thread_limit_mutex);
    thread_limit->reset();
    if (threads > 0)
        *thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                             static_cast<std::size_t>(threads));
}

int max_threads() {
    return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

}  // namespace

void bind_core(py::module_& m) {
    static py::exception<Error> error_type(m, "Error", PyExc_ValueError);
    // The message through printable(), as the CLI prints it: one line, whatever bytes it quotes.
    py::register_exception_translator([](std::exception_ptr error) {
        try {
            if (error) std::rethrow_exception(error);
        } catch (const Error& e) {
            PyErr_SetString(error_type.ptr(), printable(e.what(), kShownMessageChars).c_str());
        } catch (const py::cast_error& e) {
            // The net behind the checked conversions (text_option, bool_option, real_scalar, real_array name the
            // argument): a stray pybind11 cast is a TypeError, not RuntimeError "Unable to cast Python instance".
            PyErr_SetString(PyExc_TypeError, fmt::format("an argument has the wrong type ({})", e.what()).c_str());
        }
    });
    m.attr("Error").attr("__module__") = "surfscatter";
    m.attr("Error").attr("__doc__") =
        "Bad input to a surfscatter function: a ValueError whose message is the library's one line naming the bad "
        "value and where it came from (the same text the CLI prints after 'surfscatter: error:').";

    m.attr("__version__") = SURFSCATTER_VERSION;  // the CMake project's version, as `surfscatter --version`
    // Old spellings (docs/CONVENTIONS.md, "Names") as DeprecationWarnings at the caller's line; with warnings turned
    // into errors the warning propagates as the exception.
    set_deprecation_handler([](const std::string& message) {
        const py::gil_scoped_acquire gil;
        if (PyErr_WarnEx(PyExc_DeprecationWarning, message.c_str(), 1) != 0) throw py::error_already_set();
    });

    m.def("set_max_threads", &set_max_threads, py::arg("threads"),
          "Limits the threads of every parallel loop (Bsdf.eval/sample/pdf/albedo, the vectorised statistics, "
          "render) to `threads`; 0 restores the default (all cores). Process-wide.");
    m.def("max_threads", &max_threads, "The number of threads parallel loops may use now.");

    m.def(
        "direction",
        [](py::handle theta_deg, py::handle phi_deg) {
            const Batch batch({{theta_deg, "theta_deg"}, {phi_deg, "phi_deg"}});
            auto out = batch.output<double>(3);
            double* w = out.mutable_data();
            batch.for_each([&](std::size_t i) {
                const Vec3 v = spherical_direction(*batch.at(0, i) * kDegree, *batch.at(1, i) * kDegree);
                w[3 * i] = v.x;
                w[3 * i + 1] = v.y;
                w[3 * i + 2] = v.z;
            });
            return out;
        },
        py::arg("theta_deg"), py::arg("phi_deg") = 0.0,
        "Unit vectors (..., 3) in the local frame (z = surface normal) at polar angle theta_deg from the normal and "
        "azimuth phi_deg from +x, both in degrees, broadcast together: (sin t cos p, sin t sin p, cos t). As the "
        "CLI builds --theta-i/--phi-i and --theta-o/--phi-o directions.");
}

}  // namespace surfscatter::python

PYBIND11_MODULE(_surfscatter, m) {
    m.doc() = "Compiled core of the surfscatter package; import surfscatter instead.";
    surfscatter::python::bind_core(m);
    surfscatter::python::bind_material(m);
    surfscatter::python::bind_surface(m);
    surfscatter::python::bind_bsdf(m);
    surfscatter::python::bind_profile_lobes(m);
    surfscatter::python::bind_validity(m);
    surfscatter::python::bind_inverse(m);
    surfscatter::python::bind_render(m);
    surfscatter::python::bind_photo(m);
}
