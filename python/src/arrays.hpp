#pragma once
// numpy in and out of the library: every array argument is converted to float64 and checked (finite, and the
// domain its function documents) with an error naming the argument, the element and its value; several arguments
// broadcast to one batch shape by numpy's rules; the loop over the batch runs on TBB's threads with the GIL released.
#include <atomic>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "surfscatter/heightmap/prepare.hpp"

namespace surfscatter::python {

namespace py = pybind11;

using RealArray = py::array_t<double, py::array::c_style>;

// Values an argument accepts besides being finite.
enum class Domain {
    any,
    non_negative,     // >= 0
    positive,         // > 0
    wavelength_nm,    // > 0, in nm (the message names the unit, as the CLI's --wavelength)
    unit_interval,    // [0, 1]
    random_number,    // [0, 1): uniform random numbers
    incidence_deg,    // [0, 90): an angle of incidence in degrees (docs/CONVENTIONS.md)
    unit_vector,      // (..., 3) with |w| = 1 to kUnitTolerance
    unchecked,        // any float64 values, NaN included: the library checks them itself (height maps)
};

// Tolerance on |w|^2 - 1 for direction arguments: float32 data normalised in numpy passes, anything else is refused
// rather than silently normalised.
inline constexpr double kUnitTolerance = 1e-6;

// True if v (finite) lies in `domain` (unit_vector: see accepted_vector).
constexpr bool in_domain(double v, Domain domain) {
    switch (domain) {
        case Domain::non_negative: return v >= 0;
        case Domain::positive:
        case Domain::wavelength_nm: return v > 0;
        case Domain::unit_interval: return v >= 0 && v <= 1;
        case Domain::random_number: return v >= 0 && v < 1;
        case Domain::incidence_deg: return v >= 0 && v < 90;
        case Domain::any:
        case Domain::unit_vector:
        case Domain::unchecked: break;
    }
    return true;
}

// Finite and in the domain, without branches (v - v is 0 only for finite v).
inline bool accepted(double v, Domain domain) { return (v - v == 0.0) & in_domain(v, domain); }
// A unit vector's length test alone refuses NaN and Inf components (the comparison is false for them).
inline bool accepted_vector(const double* w, Domain domain) {
    if (domain == Domain::unit_vector) return std::abs(w[0] * w[0] + w[1] * w[1] + w[2] * w[2] - 1.0) <= kUnitTolerance;
    return accepted(w[0], domain) & accepted(w[1], domain) & accepted(w[2], domain);
}

// One array argument: `value` as the user passed it, `name` as in the Python signature. A vector argument has a last
// axis of 3 (directions, random-number triples); unit_vector arguments are vectors.
struct Arg {
    py::handle value;
    const char* name;
    Domain domain = Domain::any;
    bool vector = false;
    bool is_vector() const { return vector || domain == Domain::unit_vector; }
};

// `value` as a C-contiguous float64 array of real numbers; Error (naming `name`) for anything else: strings,
// complex or boolean data, ragged lists, a last axis other than 3 for a vector, and (with check_values) NaN, Inf
// or values outside `domain`, naming the first such element.
RealArray real_array(py::handle value, const char* name, Domain domain = Domain::any, bool vector = false,
                     bool check_values = true);

// A Python float (or int) as a double, checked like real_array's elements.
double real_scalar(py::handle value, const char* name, Domain domain = Domain::any);

// A str or a bool argument; Error naming `name` for any other type (pybind11's own cast gave RuntimeError "Unable to
// cast Python instance to C++ type").
std::string text_option(py::handle value, const char* name);
// A Python int (not a bool) of at least `least`; Error naming `name` for another type, a value beyond the 64-bit
// range or below `least` (a negative count cast to an unsigned one wrapped around).
long long integer_option(py::handle value, const char* name, long long least);
bool bool_option(py::handle value, const char* name);

// A nesting index (lambda_s_um, lambda_c_um) as the CLI and XML take it: a number (um) as its text, or a string
// ("none", "auto") as it is; heightmap::parse_lambda_s / parse_lambda_c check it.
std::string nesting_index_text(py::handle value, const char* name);

// A map's preparation from Python's keywords outliers, row_alignment, form, lambda_s_um, lambda_c_um, each checked
// under its own name (heightmap/prepare.hpp).
heightmap::Preparation preparation_arguments(const std::string& outliers, const std::string& row_alignment,
                                             const std::string& form, py::handle lambda_s_um, py::handle lambda_c_um);

// body(i) for i in [0, n), in parallel on TBB's threads, with the GIL released (the body must not touch Python
// objects). An exception thrown by the body (surfscatter::Error) reaches the caller.
template <typename Body>
void parallel_for_each(std::size_t n, const Body& body) {
    py::gil_scoped_release release;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64), [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i != range.end(); ++i) body(i);
    });
}

// Arguments broadcast together (vector arguments with their shape minus the last axis). The values of arguments
// that vary over the batch are checked element by element inside the parallel loop (for_each), where the data are
// in cache anyway (a separate pass over 10^6 directions cost as much as a GGX evaluation); single values are checked
// once, by the constructor.
class Batch {
public:
    explicit Batch(const std::vector<Arg>& args);
    Batch(const Batch&) = delete;  // varying_ points into operands_
    Batch& operator=(const Batch&) = delete;

    std::size_t size() const { return size_; }
    // Whether argument k is one value repeated over the batch (a fixed wi, a scalar wavelength).
    bool single(std::size_t k) const { return operands_[k].stride == 0; }
    // Element i of argument k (a pointer to 3 values for vector arguments).
    const double* at(std::size_t k, std::size_t i) const {
        const Operand& o = operands_[k];
        return o.data + (o.stride == 0 ? 0 : i * o.stride);
    }
    // A new array of the batch shape, with `components` values per element when components > 1.
    template <typename T>
    py::array_t<T> output(py::ssize_t components = 1) const {
        std::vector<py::ssize_t> shape = shape_;
        if (components > 1) shape.push_back(components);
        return py::array_t<T>(shape);
    }
    // body(i) for every element of the batch, in parallel without the GIL, after checking the arguments' values
    // there; if any is bad, Error naming the first bad value of the first argument that has one.
    template <typename Body>
    void for_each(const Body& body) const {
        std::atomic<bool> bad{false};
        if (varying_.size() == 1 && varying_[0]->vector) {  // one array of vectors (wo of a lobe or table): its
            const Operand& o = *varying_[0];                 // check without the loop over operands
            parallel_for_each(size_, [&](std::size_t i) {
                if (accepted_vector(o.data + 3 * i, o.domain)) body(i);
                else bad.store(true, std::memory_order_relaxed);
            });
            if (bad.load()) report_bad_values();
            return;
        }
        parallel_for_each(size_, [&](std::size_t i) {
            bool ok = true;
            for (const Operand* o : varying_)
                ok &= o->vector ? accepted_vector(o->data + i * o->stride, o->domain) : accepted(o->data[i], o->domain);
            if (ok) body(i);
            else bad.store(true, std::memory_order_relaxed);
        });
        if (bad.load()) report_bad_values();
    }

private:
    [[noreturn]] void report_bad_values() const;

    struct Operand {
        RealArray given;   // as the user gave it (for messages)
        RealArray array;   // given, or its broadcast copy
        const double* data = nullptr;
        std::size_t stride = 0;  // 0 for a single element repeated over the batch
        const char* name = nullptr;
        Domain domain = Domain::any;
        bool vector = false;
    };
    std::vector<Operand> operands_;
    std::vector<const Operand*> varying_;  // operands with more than one element, checked in for_each
    std::vector<py::ssize_t> shape_;
    std::size_t size_ = 1;
};

// What a numpy ufunc returns: a numpy scalar for a 0-d result, the array otherwise.
py::object result(const py::array& array);

// Applies f(double, ...) -> double to broadcast scalar arguments in parallel: the pattern of every vectorised
// scalar function of the module.
template <typename F>
py::object map_scalars(const std::vector<Arg>& args, const F& f) {
    const Batch batch(args);
    auto out = batch.output<double>();
    double* values = out.mutable_data();
    batch.for_each([&](std::size_t i) {
        if constexpr (std::is_invocable_v<F, double>) values[i] = f(*batch.at(0, i));
        else values[i] = f(*batch.at(0, i), *batch.at(1, i));
    });
    return result(out);
}

// numpy arrays from library data (copies).
RealArray to_array(const std::vector<double>& values);
py::array_t<float> to_float_image(const float* pixels, int height, int width, int channels);

// A str or os.PathLike as a path string; Error naming `name` otherwise.
std::string path_string(py::handle value, const char* name);

}  // namespace surfscatter::python
