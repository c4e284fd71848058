// surfscatter.render(scene, ...): render/xml_loader.hpp + render/integrator.hpp, as `surfscatter render`.
#include <atomic>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <map>
#include <mutex>
#include <optional>
#include <thread>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/scene_parameters.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::python {

namespace {

using namespace pybind11::literals;

// The params= dict as the loader's -D name=value pairs.
std::map<std::string, std::string> scene_defines(py::handle params) {
    std::map<std::string, std::string> defines;
    if (params.is_none()) return defines;
    if (!py::isinstance<py::dict>(params)) fail("params must be a dict of name: value, got {}", py::repr(params).cast<std::string>());
    for (const auto& [key, value] : params.cast<py::dict>()) {
        if (!py::isinstance<py::str>(key)) fail("params: names must be strings, got {}", py::repr(key).cast<std::string>());
        const auto name = key.cast<std::string>();
        if (!render::is_parameter_name(name))
            fail("params['{}']: a parameter name has letters, digits and '_' only (as $name in the scene)",
                 printable(name));
        if (py::isinstance<py::bool_>(value)) defines[name] = value.cast<bool>() ? "true" : "false";
        else if (py::isinstance<py::str>(value) || py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value))
            defines[name] = py::str(value).cast<std::string>();
        else fail("params['{}'] must be a string or a number, got {}", name, py::repr(value).cast<std::string>());
    }
    return defines;
}

// Runs `job` on its own thread while this one, holding the GIL every 50 ms, lets Python run its signal handlers:
// Ctrl-C then asks the renderer to stop after the current pass (core/progress.hpp), as the CLI does, and the
// job's partial result is kept. Returns the Python exception a signal handler raised (KeyboardInterrupt), if any.
template <typename Job>
std::optional<py::error_already_set> run_interruptible(const Job& job) {
    std::mutex mutex;
    std::condition_variable finished;
    bool done = false;
    std::exception_ptr failure;
    std::optional<py::error_already_set> signal;
    std::thread worker([&] {
        try {
            job();
        } catch (...) {
            failure = std::current_exception();
        }
        const std::lock_guard lock(mutex);
        done = true;
        finished.notify_one();
    });
    {
        py::gil_scoped_release release;
        std::unique_lock lock(mutex);
        while (!finished.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) {
            if (signal) continue;
            lock.unlock();
            {
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) {
                    signal.emplace();  // takes the raised exception
                    request_interrupt();
                }
            }
            lock.lock();
        }
    }
    worker.join();
    if (signal) clear_interrupt();
    if (failure) std::rethrow_exception(failure);
    return signal;
}

py::array_t<float> xyz_image(const render::Film& film) {
    std::vector<float> pixels;
    pixels.reserve(static_cast<std::size_t>(film.width()) * static_cast<std::size_t>(film.height()) * 3);
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const Vec3 v = film.xyz(x, y);
            pixels.insert(pixels.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
        }
    return to_float_image(pixels.data(), film.height(), film.width(), 3);
}

py::array_t<float> alpha_image(const render::Film& film) {
    py::array_t<float> out({static_cast<py::ssize_t>(film.height()), static_cast<py::ssize_t>(film.width())});
    float* a = out.mutable_data();
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) *a++ = static_cast<float>(film.alpha(x, y));
    return out;
}

py::dict render_scene(py::handle scene_path, std::optional<int> spp, py::handle params, long long threads,
                      std::optional<long long> seed, std::optional<double> exposure,
                      std::optional<std::string> white_balance, bool progress) {
    if (spp && *spp <= 0) fail("spp must be positive, got {}", *spp);
    require_thread_count(threads, "threads");
    if (seed && *seed < 0) fail("seed must be >= 0, got {}", *seed);
    const std::string path = path_string(scene_path, "scene");
    // A scene's text where its path belongs would otherwise be quoted whole as a file that does not exist.
    if (path.find_first_of("<\n") != std::string::npos)
        fail("scene must be the path of an .xml file, got XML text '{}' (write it to a file)", printable(path, 40));
    const auto defines = scene_defines(params);
    std::unique_ptr<render::Scene> scene;
    {
        py::gil_scoped_release release;
        scene = render::load_scene(path, render::implied_scene_parameters(path, defines), nullptr, render::ParameterSyntax::python);
    }
    // The scene's film was checked when it was loaded: what can fail now is the caller's overrides.
    if (exposure) {
        scene->film.exposure = *exposure;
        if (!(std::abs(*exposure) <= render::kMaxExposureStops))
            fail("exposure must be between -{} and {} stops, got {}", render::kMaxExposureStops,
                 render::kMaxExposureStops, *exposure);
    }
    if (white_balance) {
        scene->film.white_balance = *white_balance;
        try {
            scene->film.check();
        } catch (const Error& e) {
            fail("white_balance: {}", e.what());
        }
    }
    render::RenderOptions options;
    options.spp = spp.value_or(0);
    options.threads = static_cast<int>(threads);
    if (seed) options.seed = static_cast<std::uint64_t>(*seed);
    options.progress = progress;
    std::optional<render::Film> film;
    render::RenderStats stats;
    const auto signal = run_interruptible([&] { film.emplace(render::render(*scene, options, &stats)); });
    const io::Image rgb = film->develop(scene->film);
    if (signal) {
        if (!signal->matches(PyExc_KeyboardInterrupt)) throw *signal;
        const std::string held = stats.max_samples_per_pixel > stats.samples_per_pixel
                                     ? fmt::format("{} to {}", stats.samples_per_pixel, stats.max_samples_per_pixel)
                                     : fmt::format("{}", stats.samples_per_pixel);
        const std::string text = "surfscatter.render interrupted: its pixels hold " + held + " samples each";
        if (PyErr_WarnEx(PyExc_RuntimeWarning, text.c_str(), 1) != 0) throw py::error_already_set();
    }
    if (const std::string note = render::nonfinite_note(stats); !note.empty())
        if (PyErr_WarnEx(PyExc_RuntimeWarning, ("surfscatter.render: " + note).c_str(), 1) != 0)
            throw py::error_already_set();
    return py::dict("rgb"_a = to_float_image(rgb.pixels.data(), rgb.height, rgb.width, 3), "xyz"_a = xyz_image(*film),
                    "alpha"_a = alpha_image(*film),
                    "spp"_a = stats.samples_per_pixel, "max_spp"_a = stats.max_samples_per_pixel,
                    "interrupted"_a = stats.interrupted,
                    "seconds"_a = stats.seconds, "rays"_a = stats.rays, "nonfinite_samples"_a = stats.nonfinite_samples,
                    "notes"_a = scene->notes);
}

}  // namespace

void bind_render(py::module_& m) {
    m.def("render", &render_scene, py::arg("scene"), py::arg("spp") = py::none(), py::arg("params") = py::none(),
          py::arg("threads") = 0, py::arg("seed") = py::none(), py::arg("exposure") = py::none(),
          py::arg("white_balance") = py::none(), py::arg("progress") = false,
          R"(Renders a Mitsuba-3-style XML scene spectrally (docs/RENDERER.md), as `surfscatter render`.

scene: path of the .xml file; params: {name: value} replacing $name in the scene (the CLI's -D name=value);
spp: samples per pixel (None: the scene's sampler); threads: worker threads (0: all cores); seed: random seed
(None: the scene's); exposure: stops, overriding the film's; white_balance: 'd65' (none) or a black-body
temperature in K such as '2700', overriding the film's; progress: percentage and ETA on stderr.
Returns a dict: 'rgb' the linear sRGB image (height, width, 3) float32 after white balance and exposure (what the
CLI writes to EXR), 'xyz' the film's CIE 1931 XYZ (height, width, 3) float32 before them (Y = 1 for a constant
unit radiance), 'alpha' (height, width) float32 the film's alpha (the filter-weighted fraction of samples that hit
a shape, as Mitsuba's), 'spp' the samples every pixel got and 'max_spp' the most any pixel got (they differ only
after an interruption), 'interrupted', 'seconds', 'rays', 'notes' (the loader's remarks, e.g. the height maps it
read). Deterministic for a given seed, whatever the thread count. Ctrl-C stops the render within a sample per thread
and returns what it has, each pixel the mean of its own samples ('interrupted': True, a RuntimeWarning).)");
}

}  // namespace surfscatter::python
