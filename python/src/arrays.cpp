#include "arrays.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::python {

namespace {

py::module_ numpy() { return py::module_::import("numpy"); }

std::string shape_text(const std::vector<py::ssize_t>& shape) {
    if (shape.size() == 1) return fmt::format("({},)", shape[0]);
    return fmt::format("({})", fmt::join(shape, ", "));
}

std::vector<py::ssize_t> shape_of(const py::array& a) { return {a.shape(), a.shape() + a.ndim()}; }

// "" for a single value, " at index (2, 5)" otherwise: where in the user's array a bad element sits.
std::string where(const std::vector<py::ssize_t>& shape, std::size_t flat) {
    if (shape.empty()) return "";
    std::vector<py::ssize_t> index(shape.size());
    for (std::size_t d = shape.size(); d-- > 0;) {
        index[d] = static_cast<py::ssize_t>(flat % static_cast<std::size_t>(shape[d]));
        flat /= static_cast<std::size_t>(shape[d]);
    }
    return " at index " + shape_text(index);
}

const char* domain_text(Domain domain) {
    switch (domain) {
        case Domain::non_negative: return ">= 0";
        case Domain::positive: return "> 0";
        case Domain::wavelength_nm: return "> 0 nm";
        case Domain::unit_interval: return "in [0, 1]";
        case Domain::random_number: return "in [0, 1)";
        case Domain::incidence_deg: return "in [0, 90) degrees";
        case Domain::any:
        case Domain::unit_vector:
        case Domain::unchecked: break;
    }
    return "finite";
}

// Error unless a vector argument has a last axis of 3.
void check_shape(const RealArray& a, const char* name, bool vector) {
    if (vector && (a.ndim() == 0 || a.shape(a.ndim() - 1) != 3))
        fail("{} must have shape (..., 3), got shape {}", name, shape_text(shape_of(a)));
}

// Error naming the first value of `a` that accepted() refuses, if any.
void check_values(const RealArray& a, const char* name, Domain domain, bool vector) {
    if (domain == Domain::unchecked) return;
    const double* v = a.data();
    const auto n = static_cast<std::size_t>(a.size());
    bool ok = true;
    for (std::size_t i = 0; i < n; ++i) ok &= accepted(v[i], domain);
    if (vector)
        for (std::size_t i = 0; i < n / 3; ++i) ok &= accepted_vector(v + 3 * i, domain);
    if (ok) return;
    const auto shape = shape_of(a);
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) fail("{} must be a finite number, got {}{}", name, v[i], where(shape, i));
        if (!in_domain(v[i], domain)) fail("{} must be {}, got {}{}", name, domain_text(domain), v[i], where(shape, i));
    }
    const std::vector<py::ssize_t> batch(shape.begin(), shape.end() - 1);
    for (std::size_t i = 0; i < n / 3; ++i) {
        const double* w = v + 3 * i;
        if (!accepted_vector(w, domain))
            fail("{} must be unit vectors, got |{}| = {}{}", name, name, std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]),
                 where(batch, i));
    }
}

}  // namespace

RealArray real_array(py::handle value, const char* name, Domain domain, bool vector, bool check) {
    py::object array;
    try {
        array = numpy().attr("asarray")(value);
    } catch (const py::error_already_set& e) {
        fail("{} must be an array of real numbers ({})", name, e.what());
    }
    const auto kind = array.attr("dtype").attr("kind").cast<std::string>();
    if (kind != "f" && kind != "i" && kind != "u")
        fail("{} must hold real numbers, got dtype {}", name, py::str(array.attr("dtype")).cast<std::string>());
    // numpy casts every integer and float dtype to float64 as 'safe' but longdouble (float96/float128): it refuses
    // that cast, and its TypeError is translated here into one line naming the argument.
    auto converted = RealArray::ensure(array);
    if (!converted) {
        PyErr_Clear();
        fail("{} must hold float64 values, got dtype {} (convert it with .astype(numpy.float64) if that is exact "
             "enough)", name, py::str(array.attr("dtype")).cast<std::string>());
    }
    vector |= domain == Domain::unit_vector;
    check_shape(converted, name, vector);
    if (check) check_values(converted, name, domain, vector);
    return converted;
}

double real_scalar(py::handle value, const char* name, Domain domain) {
    const RealArray a = real_array(value, name, domain);
    if (a.ndim() != 0) fail("{} must be a single number, got an array of shape {}", name, shape_text(shape_of(a)));
    return *a.data();
}

std::string text_option(py::handle value, const char* name) {
    if (!py::isinstance<py::str>(value))
        fail("{} must be a string, got {}", name, py::repr(value).cast<std::string>());
    return value.cast<std::string>();
}

long long integer_option(py::handle value, const char* name, long long least) {
    if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value))
        fail("{} must be a whole number, got {}", name, py::repr(value).cast<std::string>());
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow != 0) fail("{} is beyond the 64-bit range, got {}", name, py::repr(value).cast<std::string>());
    if (v < least) fail("{} must be at least {}, got {}", name, least, v);
    return v;
}

bool bool_option(py::handle value, const char* name) {
    if (!py::isinstance<py::bool_>(value)) fail("{} must be True or False, got {}", name, py::repr(value).cast<std::string>());
    return value.cast<bool>();
}

std::string nesting_index_text(py::handle value, const char* name) {
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    if (py::isinstance<py::bool_>(value)) fail("{} must be a number (um) or a string, got {}", name, py::repr(value).cast<std::string>());
    return fmt::format("{:.17g}", real_scalar(value, name));
}

heightmap::Preparation preparation_arguments(const std::string& outliers, const std::string& row_alignment,
                                             const std::string& form, py::handle lambda_s_um, py::handle lambda_c_um) {
    heightmap::Preparation how;
    how.outliers = heightmap::parse_outlier_policy(outliers, "outliers");
    how.rows = heightmap::parse_row_alignment(row_alignment, "row_alignment");
    how.form = heightmap::parse_form(form, "form");
    how.lambda_s_um = heightmap::parse_lambda_s(nesting_index_text(lambda_s_um, "lambda_s_um"), "lambda_s_um");
    how.lambda_c_um = heightmap::parse_lambda_c(nesting_index_text(lambda_c_um, "lambda_c_um"), "lambda_c_um");
    return how;
}

Batch::Batch(const std::vector<Arg>& args) {
    py::list shapes;
    std::vector<std::string> described;
    for (const Arg& arg : args) {
        Operand o;
        o.given = real_array(arg.value, arg.name, arg.domain, arg.vector, false);
        o.array = o.given;
        o.name = arg.name;
        o.domain = arg.domain;
        o.vector = arg.is_vector();
        auto shape = shape_of(o.array);
        if (arg.is_vector()) shape.pop_back();
        shapes.append(py::tuple(py::cast(shape)));
        described.push_back(fmt::format("{} {}", arg.name, shape_text(shape)));
        operands_.push_back(std::move(o));
    }
    try {
        shape_ = numpy().attr("broadcast_shapes")(*shapes).cast<std::vector<py::ssize_t>>();
    } catch (const py::error_already_set&) {
        fail("the shapes of {} do not broadcast together (numpy's rules; vector arguments without their last axis "
             "of 3)", fmt::join(described, ", "));
    }
    for (py::ssize_t extent : shape_) size_ *= static_cast<std::size_t>(extent);
    for (std::size_t k = 0; k < args.size(); ++k) {
        Operand& o = operands_[k];
        const bool vector = args[k].is_vector();
        const std::size_t components = vector ? 3 : 1;
        const auto elements = static_cast<std::size_t>(o.array.size()) / components;
        if (elements == 1) {
            o.stride = 0;
            check_values(o.given, o.name, o.domain, o.vector);
        } else {
            auto full = shape_;
            if (vector) full.push_back(3);
            if (shape_of(o.array) != full)
                o.array = RealArray::ensure(numpy().attr("ascontiguousarray")(
                    numpy().attr("broadcast_to")(o.array, py::tuple(py::cast(full)))));
            o.stride = components;
        }
        o.data = o.array.data();
    }
    for (const Operand& o : operands_)
        if (o.stride != 0) varying_.push_back(&o);
    if (size_ == 0)  // no loop will see the values: check them here
        for (const Operand& o : operands_) check_values(o.given, o.name, o.domain, o.vector);
}

void Batch::report_bad_values() const {
    for (const Operand& o : operands_) check_values(o.given, o.name, o.domain, o.vector);
    fail("internal error: a value was refused but none is bad");  // unreachable: accepted() is deterministic
}

py::object result(const py::array& array) {
    if (array.ndim() == 0) return array[py::tuple()];
    return array;
}

RealArray to_array(const std::vector<double>& values) {
    RealArray out(static_cast<py::ssize_t>(values.size()));
    if (!values.empty()) std::memcpy(out.mutable_data(), values.data(), values.size() * sizeof(double));
    return out;
}

py::array_t<float> to_float_image(const float* pixels, int height, int width, int channels) {
    py::array_t<float> out({static_cast<py::ssize_t>(height), static_cast<py::ssize_t>(width),
                            static_cast<py::ssize_t>(channels)});
    std::memcpy(out.mutable_data(), pixels,
                static_cast<std::size_t>(height) * static_cast<std::size_t>(width) * static_cast<std::size_t>(channels) *
                    sizeof(float));
    return out;
}

std::string path_string(py::handle value, const char* name) {
    const py::module_ os = py::module_::import("os");
    if (!py::isinstance<py::str>(value) && !py::isinstance(value, os.attr("PathLike")))
        fail("{} must be a path (str or os.PathLike), got {}", name, py::str(py::type::of(value)).cast<std::string>());
    const py::object path = os.attr("fspath")(value);
    if (!py::isinstance<py::str>(path)) fail("{} must be a text path (str), got bytes", name);
    return path.cast<std::string>();
}

}  // namespace surfscatter::python
