// Surface statistics (surface/radial_statistics.hpp, relevant_roughness.hpp, self_convolution_table.hpp,
// refit.hpp) and height maps (height_map*.hpp, synthesis.hpp, kc_fit.hpp, psd_estimate.hpp, map_statistics.hpp).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/surface/height_map_acv.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/outliers.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/elliptical_fit.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/psd_estimate.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/refit.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::python {

namespace {

using namespace surface;
using namespace heightmap;
using namespace pybind11::literals;

constexpr const char* kFormDoc =
    "form: what is removed before the statistic: 'none' (the mean), 'plane' (tilt), 'poly2' .. 'poly4' "
    "(least-squares polynomial of that total degree), as --form.";

// A statistics method vectorised over one argument.
template <double (RadialStatistics::*method)(double) const>
py::object statistics_map(const RadialStatistics& s, py::handle x, const char* name) {
    return map_scalars({{x, name, Domain::non_negative}}, [&](double v) { return (s.*method)(v); });
}

// The pair (dx, dy) in um from a number or a pair of numbers.
std::pair<double, double> spacing_pair(py::handle spacing_um) {
    const RealArray a = real_array(spacing_um, "spacing_um", Domain::positive);
    if (a.ndim() == 0) return {*a.data(), *a.data()};
    if (a.ndim() == 1 && a.size() == 2) return {a.data()[0], a.data()[1]};
    fail("spacing_um must be one number or a pair (dx, dy), got an array of {} values", a.size());
}

std::shared_ptr<heightmap::HeightMap> height_map_from_numpy(py::handle heights_um, py::handle spacing_um, py::handle valid,
                                                 const std::string& origin) {
    const RealArray h = real_array(heights_um, "heights_um", Domain::unchecked);
    if (h.ndim() != 2) fail("heights_um must be a 2-D array (rows = y, columns = x), got {} dimensions", h.ndim());
    const auto ny = static_cast<std::size_t>(h.shape(0)), nx = static_cast<std::size_t>(h.shape(1));
    const auto [dx, dy] = spacing_pair(spacing_um);
    std::vector<double> values(h.data(), h.data() + h.size());
    if (valid.is_none()) {
        // NaN is how numpy data mark points without a measurement: say how to tell the map so (docs/PYTHON.md).
        const auto nan = std::find_if(values.begin(), values.end(), [](double v) { return std::isnan(v); });
        if (nan != values.end()) {
            const auto i = static_cast<std::size_t>(nan - values.begin());
            fail("heights_um is NaN at column {}, row {}: mark the points without data invalid, "
                 "HeightMap(heights_um, spacing_um, valid=~np.isnan(heights_um))", i % nx, i / nx);
        }
        return std::make_shared<heightmap::HeightMap>(nx, ny, dx, dy, std::move(values), origin);
    }
    const py::array mask = py::module_::import("numpy").attr("asarray")(valid);
    if (mask.dtype().kind() != 'b')
        fail("valid must be a boolean array (True = valid point), got dtype {}", py::str(mask.dtype()).cast<std::string>());
    if (mask.ndim() != 2 || static_cast<std::size_t>(mask.shape(0)) != ny || static_cast<std::size_t>(mask.shape(1)) != nx)
        fail("valid must have the shape of heights_um ({}, {})", ny, nx);
    const auto flags = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(mask);
    std::vector<std::uint8_t> validity(flags.data(), flags.data() + flags.size());
    return std::make_shared<heightmap::HeightMap>(nx, ny, dx, dy, std::move(values), std::move(validity), origin);
}

py::array_t<double> heights_array(const heightmap::HeightMap& map) {
    py::array_t<double> out({static_cast<py::ssize_t>(map.ny()), static_cast<py::ssize_t>(map.nx())});
    std::memcpy(out.mutable_data(), map.heights().data(), map.size() * sizeof(double));
    return out;
}

py::object validity_array(const heightmap::HeightMap& map) {
    if (!map.has_invalid()) return py::none();
    py::array_t<bool> out({static_cast<py::ssize_t>(map.ny()), static_cast<py::ssize_t>(map.nx())});
    bool* v = out.mutable_data();
    for (std::size_t i = 0; i < map.size(); ++i) v[i] = map.valid(i);
    return out;
}

py::dict source_dict(const heightmap::HeightMapSource& s) {
    return py::dict("format"_a = s.format, "reader"_a = s.reader, "channel"_a = s.channel, "warnings"_a = s.warnings,
                    "height_unit_um"_a = s.height_unit_um);
}

// Radial rings of a periodogram as arrays.
py::dict radial_dict(const RadialPsd& r) {
    return py::dict("zeta"_a = to_array(r.zeta), "psd"_a = to_array(r.psd), "count"_a = to_array(r.count),
                    "dzeta"_a = r.dzeta);
}

// The half-plane 2-D PSD, rows = zeta_y in FFT order, columns = zeta_x >= 0.
py::dict psd2d_dict(const Psd2d& p) {
    RealArray values({static_cast<py::ssize_t>(p.ny), static_cast<py::ssize_t>(p.half_nx())});
    std::memcpy(values.mutable_data(), p.values.data(), p.values.size() * sizeof(double));
    std::vector<double> zx(p.half_nx()), zy(p.ny);
    for (std::size_t k = 0; k < zx.size(); ++k) zx[k] = p.zeta_x(k);
    for (std::size_t k = 0; k < zy.size(); ++k) zy[k] = p.zeta_y(k);
    return py::dict("values"_a = values, "zeta_x"_a = to_array(zx), "zeta_y"_a = to_array(zy));
}

// Elliptical statistics (issue 24): KCorrelation and GaussianAcv take corr_length_v (LV, um; None: LV = corr_length)
// and lay_angle_deg, kept on the Python object beside the radial statistics (bsdf(surface=...) reads them through
// lay_of): the constructor is wrapped to take the two keywords after the radial ones.
// lay_angle_deg None is "not given" (0 deg): given without corr_length_v, even as 0, it is an error, as the CLI's
// --lay-angle without --corr-length-v.
void set_lay(py::handle self, py::object corr_length_v, py::object lay_angle_arg) {
    if (!corr_length_v.is_none()) require_surface_length(real_scalar(corr_length_v, "corr_length_v"), "corr_length_v");
    const double lay_angle_deg = lay_angle_arg.is_none() ? 0.0 : real_scalar(lay_angle_arg, "lay_angle_deg");
    require_finite(lay_angle_deg, "lay_angle_deg");
    if (corr_length_v.is_none() && !lay_angle_arg.is_none())
        fail("lay_angle_deg {} needs corr_length_v (without it the surface is isotropic)", lay_angle_deg);
    py::dict attributes = self.attr("__dict__");
    attributes["_corr_length_v"] =
        corr_length_v.is_none() ? corr_length_v : py::float_(real_scalar(corr_length_v, "corr_length_v"));
    attributes["_lay_angle_deg"] = py::float_(lay_angle_deg);
}

std::string lay_repr(py::handle self) {
    const Lay lay = lay_of(self);
    if (lay.corr_length_v == 0 && lay.lay_angle_deg == 0) return "";
    return fmt::format(", corr_length_v={}, lay_angle_deg={}",
                       lay.corr_length_v == 0 ? std::string("None") : fmt::format("{}", lay.corr_length_v),
                       lay.lay_angle_deg);
}

template <class Class>
void add_lay_keywords(Class& cls, int radial_arguments) {
    const py::object radial_init = cls.attr("__init__");
    if (radial_arguments == 3)
        cls.attr("__init__") = py::cpp_function(
            [radial_init](py::object self, py::object sigma, py::object corr_length, py::object gamma,
                          py::object corr_length_v, py::object lay_angle_deg) {
                radial_init(self, sigma, corr_length, gamma);
                set_lay(self, corr_length_v, lay_angle_deg);
            },
            py::is_method(cls), py::arg("sigma"), py::arg("corr_length"), py::arg("gamma"),
            py::arg("corr_length_v") = py::none(), py::arg("lay_angle_deg") = py::none(),
            "sigma: rms height (um); corr_length: L (um, LU along the lay), both in [1e-9, 1e9]; gamma: exponent in "
            "[1.01, 100]; corr_length_v: LV across the lay (um, None: LV = LU, isotropic); lay_angle_deg: the lay "
            "direction u from phi = 0 towards phi = 90 deg (default 0; only with corr_length_v).");
    else
        cls.attr("__init__") = py::cpp_function(
            [radial_init](py::object self, py::object sigma, py::object corr_length, py::object corr_length_v,
                          py::object lay_angle_deg) {
                radial_init(self, sigma, corr_length);
                set_lay(self, corr_length_v, lay_angle_deg);
            },
            py::is_method(cls), py::arg("sigma"), py::arg("corr_length"), py::arg("corr_length_v") = py::none(),
            py::arg("lay_angle_deg") = py::none(),
            "sigma: rms height (um); corr_length: l (um, along the lay), both in [1e-9, 1e9]; corr_length_v: across "
            "the lay (um, None: isotropic); lay_angle_deg: the lay direction from phi = 0 towards phi = 90 deg "
            "(default 0; only with corr_length_v).");
    cls.def_property_readonly(
        "corr_length_v", [](py::object self) -> py::object {
            const Lay lay = lay_of(self);
            return lay.corr_length_v == 0 ? py::object(py::none()) : py::object(py::float_(lay.corr_length_v));
        }, "LV across the lay (um), None if not given (LV = corr_length)");
    cls.def_property_readonly(
        "lay_angle_deg", [](py::object self) { return lay_of(self).lay_angle_deg; }, "lay angle A (deg)");
}

}  // namespace

Lay lay_of(py::handle statistics) {
    Lay lay;
    if (!py::hasattr(statistics, "__dict__")) return lay;
    const py::dict attributes = statistics.attr("__dict__");
    if (attributes.contains("_corr_length_v") && !attributes["_corr_length_v"].is_none())
        lay.corr_length_v = py::cast<double>(attributes["_corr_length_v"]);
    if (attributes.contains("_lay_angle_deg")) lay.lay_angle_deg = py::cast<double>(attributes["_lay_angle_deg"]);
    return lay;
}

namespace {

void bind_statistics(py::module_& m) {
    // The result types first, so that the signatures of the methods returning them name them in Python.
    py::class_<SelfConvolutionTable, std::shared_ptr<SelfConvolutionTable>>(
        m, "SelfConvolution",
        "Self-convolutions P-hat^{*m} of a unit-mass PSD, m = 1..max_order (RadialStatistics.self_convolution).")
        .def_property_readonly("max_order", &SelfConvolutionTable::max_order, "highest order m tabulated")
        .def(
            "psd_unit",
            [](const SelfConvolutionTable& t, int order, py::handle zeta) {
                return map_scalars({{zeta, "zeta", Domain::non_negative}}, [&](double z) { return t.eval(order, z); });
            },
            py::arg("m"), py::arg("zeta"), "P-hat^{*m}(zeta) in um^2 at zeta >= 0 (rad/um), m in 1..max_order.")
        .def(
            "radial_cdf",
            [](const SelfConvolutionTable& t, int order, py::handle zeta) {
                return map_scalars({{zeta, "zeta", Domain::non_negative}}, [&](double z) { return t.radial_cdf(order, z); });
            },
            py::arg("m"), py::arg("zeta"), "Mass of P-hat^{*m} inside |zeta'| <= zeta (rad/um).")
        .def(
            "inverse_radial_cdf",
            [](const SelfConvolutionTable& t, int order, py::handle u) {
                return map_scalars({{u, "u", Domain::random_number}}, [&](double v) { return t.inverse_radial_cdf(order, v); });
            },
            py::arg("m"), py::arg("u"), "Radius (rad/um) at which the radial CDF of order m reaches u in [0, 1).");

    py::class_<RefitResult>(m, "Refit", "Result of KCorrelation.refit: L_m = L m^-x (THEORY.md 2.4).")
        .def_readonly("exponent_x", &RefitResult::exponent_x, "x of L_m = L m^-x")
        .def_property_readonly(
            "corr_length_um", [](const RefitResult& r) { return to_array(r.corr_length_m); },
            "the fitted L_m (um) for m = 1..max_order (index m - 1)")
        .def_property_readonly(
            "misfit", [](const RefitResult& r) { return to_array(r.misfit_m); },
            "integral of |fit - true| over the zeta-plane (fraction of unit mass), index m - 1")
        .def("__repr__", [](const RefitResult& r) {
            return fmt::format("surfscatter.Refit(exponent_x={}, orders={})", r.exponent_x, r.corr_length_m.size());
        });

    py::class_<RadialStatistics, std::shared_ptr<RadialStatistics>>(
        m, "RadialStatistics",
        "Isotropic surface statistics (THEORY.md 0, 2): radial PSD P(zeta) in um^4 over the angular spatial "
        "frequency zeta (rad/um), normalised so that its integral over the zeta-plane is sigma_h^2, and "
        "autocovariance C(r) in um^2 over the lateral distance r (um). Base of KCorrelation, GaussianAcv and "
        "TabulatedPsd; every method is vectorised over its array arguments (numpy broadcasting).")
        .def_property_readonly("sigma_h", &RadialStatistics::sigma_h, "rms height sigma_h (um)")
        .def_property_readonly("correlation_length", &RadialStatistics::correlation_length,
                               "characteristic length (um) that scales the tables")
        .def_property_readonly("cache_key", &RadialStatistics::cache_key, "text naming the model and its parameters")
        .def(
            "psd", [](const RadialStatistics& s, py::handle zeta) { return statistics_map<&RadialStatistics::psd>(s, zeta, "zeta"); },
            py::arg("zeta"), "P(zeta) in um^4 at angular frequencies zeta >= 0 (rad/um), as `surfscatter psd`.")
        .def(
            "psd_unit",
            [](const RadialStatistics& s, py::handle zeta) { return statistics_map<&RadialStatistics::psd_unit>(s, zeta, "zeta"); },
            py::arg("zeta"), "P(zeta) / sigma_h^2 in um^2 (unit mass over the zeta-plane), zeta >= 0 in rad/um.")
        .def(
            "acv", [](const RadialStatistics& s, py::handle r_um) { return statistics_map<&RadialStatistics::acv>(s, r_um, "r_um"); },
            py::arg("r_um"), "C(r) in um^2 at lateral distances r_um >= 0 (um), as `surfscatter acv`.")
        .def(
            "acv_normalized",
            [](const RadialStatistics& s, py::handle r_um) { return statistics_map<&RadialStatistics::acv_normalized>(s, r_um, "r_um"); },
            py::arg("r_um"), "rho(r) = C(r) / sigma_h^2 (rho(0) = 1) at lateral distances r_um >= 0 (um).")
        .def(
            "radial_cdf",
            [](const RadialStatistics& s, py::handle zeta) { return statistics_map<&RadialStatistics::radial_cdf>(s, zeta, "zeta"); },
            py::arg("zeta"), "Mass of P/sigma_h^2 inside |zeta'| <= zeta (rad/um), in [0, 1].")
        .def(
            "relevant_roughness",
            [](const RadialStatistics& s, py::handle theta_i_deg, py::handle lambda_nm) {
                return map_scalars({{theta_i_deg, "theta_i_deg", Domain::incidence_deg},
                                    {lambda_nm, "lambda_nm", Domain::wavelength_nm}},
                                   [&](double t, double l) { return relevant_roughness(s, t * kDegree, l); });
            },
            py::arg("theta_i_deg"), py::arg("lambda_nm"),
            "sigma_rel (um): the rms height of the part of the PSD inside the visible disc for incidence "
            "theta_i_deg in [0, 90) degrees and wavelength lambda_nm (nm), broadcast together (THEORY.md 1.1).")
        .def(
            "visible_disc_mass",
            [](const RadialStatistics& s, py::handle theta_i_deg, py::handle lambda_nm) {
                return map_scalars({{theta_i_deg, "theta_i_deg", Domain::incidence_deg},
                                    {lambda_nm, "lambda_nm", Domain::wavelength_nm}},
                                   [&](double t, double l) { return visible_disc_mass(s, t * kDegree, l); });
            },
            py::arg("theta_i_deg"), py::arg("lambda_nm"),
            "(sigma_rel / sigma_h)^2: the fraction of the PSD's mass inside the visible disc, broadcast over "
            "theta_i_deg in [0, 90) degrees and lambda_nm (nm).")
        .def(
            "total_integrated_scatter",
            [](const RadialStatistics& s, py::handle theta_i_deg, py::handle lambda_nm) {
                return map_scalars({{theta_i_deg, "theta_i_deg", Domain::incidence_deg},
                                    {lambda_nm, "lambda_nm", Domain::wavelength_nm}},
                                   [&](double t, double l) { return s.total_integrated_scatter(t * kDegree, l); });
            },
            py::arg("theta_i_deg"), py::arg("lambda_nm"),
            "1 - exp(-(4 pi sigma_rel / lambda)^2) of a perfect conductor (THEORY.md 1.1), broadcast over "
            "theta_i_deg in [0, 90) degrees and lambda_nm (nm).")
        .def(
            "mean_square_slope",
            [](const RadialStatistics& s, double smoothing_um, double cutoff_zeta) {
                return s.mean_square_slope(smoothing_um, cutoff_zeta);
            },
            py::arg("smoothing_um") = 0.0, py::arg("cutoff_zeta") = std::numeric_limits<double>::infinity(),
            "<|grad h|^2> (dimensionless) after Gaussian smoothing of standard deviation smoothing_um (um; 0 = none) "
            "and a sharp low-pass at cutoff_zeta (rad/um; inf = none); inf when the integral diverges.")
        .def(
            "self_convolution",
            [](const RadialStatistics& s, long long max_order) {
                require_refit_orders(max_order, "max_order");
                py::gil_scoped_release release;
                return std::const_pointer_cast<SelfConvolutionTable>(SelfConvolutionTable::get(s, static_cast<int>(max_order)));
            },
            py::arg("max_order"),
            "The self-convolutions P-hat^{*m}, m = 1..max_order, of the unit-mass PSD (THEORY.md 1.2, 2.3), "
            "tabulated once and cached on disk: a SelfConvolution.");

    py::class_<KCorrelation, RadialStatistics, std::shared_ptr<KCorrelation>> kc_class(
        m, "KCorrelation", py::dynamic_attr(),
        "K-correlation (ABC) statistics, THEORY.md 2.1: P = sigma^2 (gamma - 1) L^2 / (2 pi) "
        "(1 + L^2 zeta^2)^(-(gamma + 1)/2). Parameters named as in the XML and ModelOptions. corr_length_v (um, "
        "None: = corr_length) and lay_angle_deg make it elliptical for bsdf(surface=...) (docs/SURFACE.md "
        "\"Anisotropy\"); the methods here are those of the radial statistics along the lay (corr_length).");
    kc_class
        .def(py::init([](double sigma, double corr_length, double gamma) {
                 require_surface_length(sigma, "sigma");  // the user's ranges, as the CLI and the scenes check them
                 require_surface_length(corr_length, "corr_length");
                 require_kc_gamma(gamma, "gamma");
                 return std::make_shared<KCorrelation>(sigma, corr_length, gamma);
             }),
             py::arg("sigma"), py::arg("corr_length"), py::arg("gamma"),
             "sigma: rms height (um); corr_length: L (um), both in [1e-9, 1e9]; gamma: exponent in [1.01, 100].")
        .def_property_readonly("gamma", &KCorrelation::gamma, "exponent gamma")
        .def(
            "inverse_radial_cdf",
            [](const KCorrelation& s, py::handle u) {
                return map_scalars({{u, "u", Domain::random_number}}, [&](double v) { return s.inverse_radial_cdf(v); });
            },
            py::arg("u"), "zeta (rad/um) with radial_cdf(zeta) = u, for u in [0, 1).")
        .def_property_readonly(
            "abc",
            [](const KCorrelation& s) {
                const AbcParameters p = to_abc(s);
                return py::dict("a"_a = p.a, "b"_a = p.b, "c"_a = p.c);
            },
            "ABC (Church) parameters in cyclic frequency: {'a': um^4, 'b': um, 'c': = gamma}.")
        .def_static(
            "from_abc", [](double a, double b, double c) { return from_abc({a, b, c}); }, py::arg("a"),
            py::arg("b"), py::arg("c"), "The KCorrelation of ABC parameters a (um^4), b (um), c (> 1).")
        .def(
            "refit",
            [](const KCorrelation& s, long long max_order) {
                require_refit_orders(max_order, "max_order");
                py::gil_scoped_release release;
                return refit_self_convolutions(s, static_cast<int>(max_order));
            },
            py::arg("max_order"),
            "The supplemental's refit (THEORY.md 2.4): each self-convolution m = 1..max_order fitted by a KC of "
            "the same gamma, then L_m = L m^-x. A Refit; as `surfscatter selfconv`.")
        .def("__repr__", [](py::object self) {
            const auto& s = self.cast<const KCorrelation&>();
            return fmt::format("surfscatter.KCorrelation(sigma={}, corr_length={}, gamma={}{})", s.sigma_h(),
                               s.correlation_length(), s.gamma(), lay_repr(self));
        });
    add_lay_keywords(kc_class, 3);

    py::class_<GaussianAcv, RadialStatistics, std::shared_ptr<GaussianAcv>> gaussian_class(
        m, "GaussianAcv", py::dynamic_attr(),
        "Gaussian autocovariance C(r) = sigma^2 exp(-r^2 / corr_length^2); corr_length_v and lay_angle_deg as for "
        "KCorrelation.");
    gaussian_class
        .def(py::init([](double sigma, double corr_length) {
                 require_surface_length(sigma, "sigma");
                 require_surface_length(corr_length, "corr_length");
                 return std::make_shared<GaussianAcv>(sigma, corr_length);
             }),
             py::arg("sigma"), py::arg("corr_length"), "sigma: rms height (um); corr_length: l (um), both in [1e-9, 1e9].")
        .def(
            "inverse_radial_cdf",
            [](const GaussianAcv& s, py::handle u) {
                return map_scalars({{u, "u", Domain::random_number}}, [&](double v) { return s.inverse_radial_cdf(v); });
            },
            py::arg("u"), "zeta (rad/um) with radial_cdf(zeta) = u, for u in [0, 1).")
        .def("__repr__", [](py::object self) {
            const auto& s = self.cast<const GaussianAcv&>();
            return fmt::format("surfscatter.GaussianAcv(sigma={}, corr_length={}{})", s.sigma_h(),
                               s.correlation_length(), lay_repr(self));
        });
    add_lay_keywords(gaussian_class, 2);

    py::class_<TabulatedPsd, RadialStatistics, std::shared_ptr<TabulatedPsd>>(
        m, "TabulatedPsd",
        "Statistics of a measured radial PSD: log-log interpolation between samples, flat below the first, the "
        "last decade's power law beyond the last (which must fall faster than zeta^-2).")
        .def(py::init([](py::handle zeta, py::handle psd) {
                 const RealArray z = real_array(zeta, "zeta", Domain::positive);
                 const RealArray p = real_array(psd, "psd", Domain::positive);
                 if (z.ndim() != 1 || p.ndim() != 1 || z.size() != p.size())
                     fail("zeta and psd must be 1-D arrays of the same length, got {} and {} values", z.size(), p.size());
                 return std::make_shared<TabulatedPsd>(std::vector<double>(z.data(), z.data() + z.size()),
                                                       std::vector<double>(p.data(), p.data() + p.size()));
             }),
             py::arg("zeta"), py::arg("psd"),
             "zeta: strictly increasing angular frequencies (rad/um); psd: P at them (um^4, > 0).")
        .def("__repr__", [](const TabulatedPsd& s) {  // short: the whole table (cache_key) is kilobytes
            return fmt::format("<surfscatter.TabulatedPsd sigma={:.4g} um, data zeta {:.3g}..{:.3g} rad/um, tail "
                               "zeta^{:.2f}>", s.sigma_h(), s.first_zeta(), s.last_zeta(), s.tail_slope());
        });
}

void bind_height_maps(py::module_& m) {
    py::class_<heightmap::HeightMap, std::shared_ptr<heightmap::HeightMap>>(
        m, "HeightMap",
        "A height map h(x, y) on a regular grid: heights and spacings in um, an optional validity mask. numpy "
        "layout: heights_um[iy, ix] (rows along y, x along a row), as Gwyddion stores them.")
        .def(py::init(&height_map_from_numpy), py::arg("heights_um"), py::arg("spacing_um"),
             py::arg("valid") = py::none(), py::arg("origin") = "numpy array",
             "heights_um: 2-D array (ny, nx) of heights in um, finite at every valid point; spacing_um: pixel "
             "spacing in um, one number or (dx, dy); valid: None (all valid) or a boolean array of the same shape "
             "(False = invalid point: its height is ignored and may be NaN); origin: names the data in messages.")
        .def_property_readonly("heights_um", &heights_array, "heights (ny, nx) in um (a copy; invalid points hold 0)")
        .def_property_readonly("valid", &validity_array, "boolean mask (ny, nx), or None when every point is valid")
        .def_property_readonly("nx", &heightmap::HeightMap::nx, "points along x (columns)")
        .def_property_readonly("ny", &heightmap::HeightMap::ny, "points along y (rows)")
        .def_property_readonly("spacing_x_um", &heightmap::HeightMap::spacing_x, "pixel spacing along x (um)")
        .def_property_readonly("spacing_y_um", &heightmap::HeightMap::spacing_y, "pixel spacing along y (um)")
        .def_property_readonly("width_um", &heightmap::HeightMap::width, "nx * dx (um)")
        .def_property_readonly("height_um", &heightmap::HeightMap::height, "ny * dy (um)")
        .def_property_readonly("valid_fraction", &heightmap::HeightMap::valid_fraction, "fraction of the points that are valid")
        .def_property_readonly("origin", &heightmap::HeightMap::origin, "where the data came from (file name)")
        .def_readwrite("title", &heightmap::HeightMap::title, "title stored in .gsf files")
        .def_property_readonly(
            "source", [](const heightmap::HeightMap& h) { return source_dict(h.source); },
            "what the reader found: {'format', 'reader', 'channel', 'warnings', 'height_unit_um'}")
        .def("describe", static_cast<std::string (*)(const heightmap::HeightMap&)>(&describe),
             "one line: file, format, grid, spacing, valid fraction")
        .def("__repr__", [](const heightmap::HeightMap& h) { return "<surfscatter.HeightMap " + describe(h) + ">"; })
        .def(
            "remove_form", [](const heightmap::HeightMap& h, const std::string& form) { return heightmap::remove_form(h, heightmap::parse_form(form, "form")); },
            py::arg("form") = "plane", (std::string("The map minus its least-squares form. ") + kFormDoc).c_str())
        .def(
            "outliers",
            [](const heightmap::HeightMap& h) {
                const heightmap::Outliers o = heightmap::find_outliers(h);
                return py::dict("points"_a = o.count, "spots"_a = o.spots, "robust_sigma_um"_a = o.robust_sigma_um,
                                "largest_um"_a = o.largest_um, "share"_a = o.share, "dominant"_a = o.dominant(),
                                "text"_a = describe(o));
            },
            "Points far from their 5 x 5 neighbourhood (docs/HEIGHTMAPS.md \"Outliers\"): {'points', 'spots', "
            "'robust_sigma_um', 'largest_um' (the largest residual), 'share' (of the pixel-scale roughness), "
            "'dominant' (share > 0.5), 'text'}")
        .def(
            "prepare",
            [](const heightmap::HeightMap& h, const std::string& outliers, const std::string& row_alignment,
               const std::string& form, py::handle lambda_s_um, py::handle lambda_c_um) {
                const heightmap::Preparation how =
                    preparation_arguments(outliers, row_alignment, form, lambda_s_um, lambda_c_um);
                heightmap::PreparedMap p = [&] {
                    py::gil_scoped_release release;
                    return heightmap::prepare(h, how);
                }();
                const std::string text = heightmap::describe(p);
                py::object waviness = py::none();
                if (p.waviness) waviness = py::cast(std::make_shared<heightmap::HeightMap>(std::move(*p.waviness)));
                return py::dict("map"_a = std::make_shared<heightmap::HeightMap>(std::move(p.map)),
                                "waviness"_a = waviness, "outliers"_a = p.outliers.count,
                                "rows_aligned"_a = p.rows_aligned, "row_offsets_rms_um"_a = p.rows.rms_um,
                                "lambda_c_um"_a = p.applied.lambda_c_um.value_or(0.0), "read_rms_um"_a = p.read_rms_um,
                                "form_rms_um"_a = p.form_rms_um, "short_rms_um"_a = p.short_rms_um,
                                "waviness_rms_um"_a = p.waviness_rms_um, "text"_a = text);
            },
            py::arg("outliers") = "keep", py::arg("row_alignment") = "auto", py::arg("form") = "plane",
            py::arg("lambda_s_um") = "none", py::arg("lambda_c_um") = "auto",
            "The map as the models and references prepare it (docs/HEIGHTMAPS.md \"Preparation\"): outliers "
            "'keep' | 'fill', row_alignment 'auto' | 'median' | 'none', form, lambda_s_um (um or 'none'), lambda_c_um "
            "(um, 'none' or 'auto'). Returns {'map' (the prepared HeightMap), 'waviness' (what the L-filter removed, "
            "or None), 'outliers' (points found), 'rows_aligned', 'row_offsets_rms_um', 'lambda_c_um' (0: none), "
            "'read_rms_um', 'form_rms_um', 'short_rms_um', 'waviness_rms_um' (the rms of what each step removed), "
            "'text' (the steps in one line)}")
        .def(
            "fill_outliers", [](const heightmap::HeightMap& h) { return heightmap::fill_outliers(h, heightmap::find_outliers(h)); },
            "The map with each outlier replaced by the median of its neighbours that are not (what outliers='fill' "
            "does before the statistics)")
        .def(
            "rms_height", [](const heightmap::HeightMap& h, const std::string& form) { return heightmap::rms_height(h, heightmap::parse_form(form, "form")); },
            py::arg("form") = "plane", (std::string("rms height (um) about the form over the valid points. ") + kFormDoc).c_str())
        .def(
            "rms_slope",
            [](const heightmap::HeightMap& h, const std::string& form, std::optional<double> smoothing_um) {
                const heightmap::Form f = heightmap::parse_form(form, "form");
                if (!smoothing_um) return rms_slope(h, f);
                require_smoothing(*smoothing_um, h, "smoothing_um");
                return rms_slope_smoothed(h, *smoothing_um, f);
            },
            py::arg("form") = "plane", py::arg("smoothing_um") = py::none(),
            (std::string("rms slope (central differences) of the form-removed map, after Gaussian smoothing of "
                         "standard deviation smoothing_um (um) if given. ") + kFormDoc).c_str())
        .def(
            "moments",
            [](const heightmap::HeightMap& h, const std::string& form) {
                const heightmap::HeightMoments hm = heightmap::height_moments(heightmap::remove_form(h, heightmap::parse_form(form, "form")));
                return py::dict("rms"_a = hm.rms, "skewness"_a = hm.skewness, "kurtosis"_a = hm.kurtosis);
            },
            py::arg("form") = "plane",
            (std::string("{'rms' (um), 'skewness', 'kurtosis'} of the form-removed map, as `surface info`. ") + kFormDoc).c_str())
        .def(
            "acv_measures",
            [](const heightmap::HeightMap& h, const std::string& form) {
                const AcvMeasures a = acv_measures(heightmap::remove_form(h, heightmap::parse_form(form, "form")));
                return py::dict("correlation_length_um"_a = a.correlation_length_um,
                                "autocorrelation_length_um"_a = a.autocorrelation_length_um,
                                "texture_aspect_ratio"_a = a.texture_aspect_ratio, "str_is_bound"_a = a.str_is_bound,
                                "slowest_direction_deg"_a = a.slowest_direction_deg);
            },
            py::arg("form") = "plane",
            (std::string("ACF measures of the form-removed map (height_map_acv.hpp): correlation length (1/e), "
                         "Sal and Str (ISO 25178-2, s = 0.2), as `surface info`. ") + kFormDoc).c_str())
        .def(
            "psd",
            [](const heightmap::HeightMap& h, const std::string& form) {
                const Psd2d p = estimate_psd(h, Window::hann, heightmap::parse_form(form, "form"));
                py::dict out = psd2d_dict(p);
                out["radial"] = radial_dict(radial_average(p));
                return out;
            },
            py::arg("form") = "plane",
            (std::string("Hann-windowed periodogram of the form-removed map (psd_estimate.hpp): {'values': "
                         "half-plane P (ny, nx//2 + 1) in um^4, 'zeta_x', 'zeta_y' (rad/um, zeta_y in FFT order), "
                         "'radial': {'zeta', 'psd', 'count', 'dzeta'}}. ") + kFormDoc).c_str())
        .def(
            "write", [](const heightmap::HeightMap& h, py::handle path) { heightmap::write_height_map(h, path_string(path, "path")); },
            py::arg("path"), "Writes .gsf or .gwy (by extension), heights in m as Gwyddion writes them.");

    m.def(
        "read_height_map",
        [](py::handle path, std::optional<double> spacing_um, std::optional<double> height_unit_um) {
            const std::string file = path_string(path, "path");
            py::gil_scoped_release release;
            return std::make_shared<heightmap::HeightMap>(heightmap::read_height_map(file, spacing_um, height_unit_um));
        },
        py::arg("path"), py::arg("spacing_um") = py::none(), py::arg("height_unit_um") = py::none(),
        "Reads any height map: every format Gwyddion reads (.gwy, .gsf, .sdf, MetroPro .dat, .opd, Nanoscope, ...), "
        "X3P, Gwyddion's text export, or a CSV/whitespace grid (docs/HEIGHTMAPS.md). spacing_um and height_unit_um "
        "(um per height unit) are needed for a bare text grid; for files that state them they may only agree.");

    m.def(
        "synthesize",
        [](py::handle statistics_arg, py::handle size, double spacing_um, long long seed) {
            if (!py::isinstance<RadialStatistics>(statistics_arg))
                fail("statistics must be a KCorrelation or a GaussianAcv, got {}", py::repr(statistics_arg).cast<std::string>());
            const auto statistics = statistics_arg.cast<std::shared_ptr<RadialStatistics>>();
            if (seed < 0) fail("seed must be >= 0, got {}", seed);
            std::size_t nx = 0, ny = 0;
            const auto count = [&size](py::handle n) {
                if (!py::isinstance<py::int_>(n) || py::isinstance<py::bool_>(n) || n.cast<long long>() < 0)
                    fail("size must be n or (nx, ny) (whole numbers of samples), got {}", py::repr(size).cast<std::string>());
                return n.cast<std::size_t>();
            };
            if (py::isinstance<py::sequence>(size) && !py::isinstance<py::str>(size) && py::len(size) == 2)
                nx = count(size[py::int_(0)]), ny = count(size[py::int_(1)]);
            else nx = ny = count(size);
            const SynthesisGrid grid{nx, ny, spacing_um};
            // An elliptical KCorrelation or GaussianAcv (corr_length_v, lay_angle_deg) is synthesised with its lay.
            const Lay lay = lay_of(statistics_arg);
            py::gil_scoped_release release;
            if (lay.corr_length_v != 0)
                return std::make_shared<heightmap::HeightMap>(synthesize_surface(
                    EllipticalStatistics(statistics, lay.corr_length_v, lay.lay_angle_deg * kDegree), grid,
                    static_cast<std::uint64_t>(seed)));
            return std::make_shared<heightmap::HeightMap>(synthesize_surface(*statistics, grid, static_cast<std::uint64_t>(seed)));
        },
        py::arg("statistics"), py::arg("size"), py::arg("spacing_um"), py::arg("seed") = 1,
        "A random Gaussian surface with the PSD of `statistics` (spectral synthesis, synthesis.hpp) on an n x n "
        "(size = n) or nx x ny (size = (nx, ny)) grid of spacing_um; the same seed gives the same surface as "
        "`surfscatter surface synth --seed`; elliptical statistics (made with corr_length_v) with their lay, as "
        "`surface synth --corr-length-v --lay-angle`.");

    py::class_<MapStatistics, RadialStatistics, std::shared_ptr<MapStatistics>>(
        m, "MapStatistics",
        "A height map's own statistics, what psd 'measured' uses (map_statistics.hpp): its periodogram's ring means "
        "from the first ring to Nyquist (rolled off beyond), linear below the first ring from the DC bin, which is continued from the lattice's lowest ring.")
        .def_property_readonly("map_rms", &MapStatistics::map_rms, "rms of the form-removed map (um)")
        .def_property_readonly("sigma_standard_error", &MapStatistics::sigma_relative_error,
                               "relative standard error of sigma_h for a random surface of this spectrum")
        .def_property_readonly("periodic", &MapStatistics::periodic, "True: the map wraps around (rectangular window)")
        .def_property_readonly("first_ring", &MapStatistics::first_ring, "lowest frequency resolved (rad/um)")
        .def_property_readonly("ring_width", &MapStatistics::ring_width, "rad/um")
        .def_property_readonly("nyquist", &MapStatistics::nyquist, "top of the band (rad/um)")
        .def_property_readonly("below_band_fraction", &MapStatistics::below_band_fraction,
                               "share of sigma_h^2 below the first ring")
        .def_property_readonly("above_band_fraction", &MapStatistics::above_band_fraction,
                               "share of sigma_h^2 rolled off beyond Nyquist")
        .def(
            "ring_samples",
            [](const MapStatistics& s, py::handle zeta) {
                return map_scalars({{zeta, "zeta", Domain::non_negative}}, [&](double z) { return s.ring_samples(z); });
            },
            py::arg("zeta"), "independent periodogram samples of the ring holding zeta (relative error 1/sqrt)")
        .def("__repr__", [](const MapStatistics& s) {
            return fmt::format("<surfscatter.MapStatistics sigma={:.4g} um (map rms {:.4g} um, +-{:.2g} %), band "
                               "{:.3g}..{:.3g} rad/um, {} window>",
                               s.sigma_h(), s.map_rms(), 100.0 * s.sigma_relative_error(), s.first_ring(), s.nyquist(),
                               s.periodic() ? "rectangular" : "Hann");
        });

    m.def(
        "measured_statistics",
        [](const heightmap::HeightMap& map, const std::string& form) {
            const heightmap::Form f = heightmap::parse_form(form, "form");
            py::gil_scoped_release release;
            return std::make_shared<MapStatistics>(map, f);
        },
        py::arg("height_map"), py::arg("form") = "plane",
        "The map's own statistics after removing `form`, what psd 'measured' uses: a MapStatistics "
        "(docs/HEIGHTMAPS.md).");

    py::class_<SurfaceFit>(m, "SurfaceFit",
                           "A KC fit to a height map (fit_surface), with the names `surfscatter surface fit` prints.")
        .def_property_readonly("sigma_h", [](const SurfaceFit& f) { return f.kc.sigma_h_um; }, "fitted sigma_h (um)")
        .def_property_readonly("corr_length", [](const SurfaceFit& f) { return f.kc.corr_length_um; }, "fitted L (um)")
        .def_property_readonly("gamma", [](const SurfaceFit& f) { return f.kc.gamma; }, "fitted gamma")
        .def_property_readonly("zeta_min", [](const SurfaceFit& f) { return f.kc.zeta_min; }, "band used, rad/um")
        .def_property_readonly("zeta_max", [](const SurfaceFit& f) { return f.kc.zeta_max; }, "band used, rad/um")
        .def_property_readonly("rings", [](const SurfaceFit& f) { return f.kc.rings; }, "rings in the band")
        .def_property_readonly("log_residual_rms", [](const SurfaceFit& f) { return f.kc.log_residual_rms; },
                               "weighted rms of ln(data / model)")
        .def_readonly("rms_height_map", &SurfaceFit::rms_height_um, "rms of the form-removed map (um, band-limited)")
        .def_readonly("fit_lattice_rms", &SurfaceFit::fit_lattice_rms_um,
                      "the fitted KC's rms summed over the map's own frequencies (um)")
        .def_readonly("map_lattice_rms", &SurfaceFit::map_lattice_rms_um, "the map's periodogram's rms there (um)")
        .def_property_readonly("lattice_warning", &lattice_rms_check,
                               "why the fit's rms on the map's frequencies disagrees with the map's, or ''")
        .def_readonly("rms_slope", &SurfaceFit::rms_slope, "rms slope of the form-removed map (central differences)")
        .def_readonly("rms_slope_psd", &SurfaceFit::rms_slope_from_psd, "rms slope from the 2-D periodogram")
        .def_property_readonly(
            "statistics",
            [](const SurfaceFit& f) { return std::make_shared<KCorrelation>(f.kc.sigma_h_um, f.kc.corr_length_um, f.kc.gamma); },
            "the fitted KCorrelation")
        .def_property_readonly("radial", [](const SurfaceFit& f) { return radial_dict(f.radial); },
                               "the rings that were fitted: {'zeta' (rad/um), 'psd' (um^4), 'count', 'dzeta'}")
        .def_property_readonly("psd2d", [](const SurfaceFit& f) { return psd2d_dict(f.psd); },
                               "the 2-D periodogram: {'values' (ny, nx//2 + 1), 'zeta_x', 'zeta_y'}")
        .def_property_readonly(
            "elliptical",
            [](const SurfaceFit& f) -> py::object {
                if (!f.elliptical.failure.empty()) return py::none();
                return py::cast(f.elliptical);
            },
            "the elliptical KC fit (an EllipticalFit), None where it does not resolve (fit_elliptical says why)")
        .def_property_readonly(
            "corr_length_v",
            [](const SurfaceFit& f) -> py::object {
                if (!f.elliptical.failure.empty()) return py::none();
                return py::float_(f.elliptical.corr_length_v_um);
            },
            "the elliptical fit's LV (um; its corr_length is elliptical.corr_length), None where it does not resolve")
        .def_property_readonly(
            "lay_angle_deg",
            [](const SurfaceFit& f) -> py::object {
                if (!f.elliptical.failure.empty()) return py::none();
                return py::float_(f.elliptical.lay_angle_deg);
            },
            "the elliptical fit's lay angle (deg), None where it does not resolve")
        .def("__repr__", [](const SurfaceFit& f) {
            return fmt::format("surfscatter.SurfaceFit(sigma_h={}, corr_length={}, gamma={})", f.kc.sigma_h_um,
                               f.kc.corr_length_um, f.kc.gamma);
        });

    py::class_<EllipticalKcFit>(
        m, "EllipticalFit",
        "An elliptical KC fit to a height map's 2-D periodogram (elliptical_fit.hpp; issue 24's convention: corr_length "
        "LU along the lay angle, corr_length_v LV across it, LU >= LV, lay_angle_deg in [0, 180) from +x towards +y), "
        "with standard errors; the names of `surfscatter surface fit`'s elliptical_* lines.")
        .def_readonly("sigma_h", &EllipticalKcFit::sigma_h_um, "fitted sigma_h (um)")
        .def_readonly("corr_length", &EllipticalKcFit::corr_length_u_um, "LU (um), along the lay")
        .def_readonly("corr_length_v", &EllipticalKcFit::corr_length_v_um, "LV (um), across the lay")
        .def_readonly("gamma", &EllipticalKcFit::gamma, "fitted gamma")
        .def_readonly("lay_angle_deg", &EllipticalKcFit::lay_angle_deg, "lay angle A (deg, [0, 180))")
        .def_readonly("sigma_h_error", &EllipticalKcFit::sigma_h_error_um, "standard error (um)")
        .def_readonly("corr_length_error", &EllipticalKcFit::corr_length_u_error_um, "standard error (um)")
        .def_readonly("corr_length_v_error", &EllipticalKcFit::corr_length_v_error_um, "standard error (um)")
        .def_readonly("gamma_error", &EllipticalKcFit::gamma_error, "standard error")
        .def_readonly("lay_angle_error_deg", &EllipticalKcFit::lay_angle_error_deg,
                      "standard error (deg; 90 = undetermined)")
        .def_property_readonly("axis_ratio", &EllipticalKcFit::axis_ratio, "LV / LU")
        .def_readonly("axis_ratio_error", &EllipticalKcFit::axis_ratio_error, "standard error of LV / LU")
        .def_readonly("anisotropy_chi2", &EllipticalKcFit::anisotropy_chi2, "Wald statistic against isotropy (2 dof)")
        .def_property_readonly("anisotropic", &EllipticalKcFit::anisotropic,
                               "whether the anisotropy is significant (anisotropy_chi2 > 13.8)")
        .def_readonly("misfit", &EllipticalKcFit::log_residual_rms, "weighted rms of ln(data / model) over the cells")
        .def_readonly("statistical_floor", &EllipticalKcFit::statistical_floor,
                      "what misfit is for an elliptical KC surface")
        .def_readonly("cells", &EllipticalKcFit::cells, "polar cells fitted")
        .def("__repr__", [](const EllipticalKcFit& f) {
            return fmt::format("surfscatter.EllipticalFit(sigma_h={}, corr_length={}, corr_length_v={}, gamma={}, "
                               "lay_angle_deg={})",
                               f.sigma_h_um, f.corr_length_u_um, f.corr_length_v_um, f.gamma, f.lay_angle_deg);
        });

    const auto fit_options = [](const std::string& form, std::size_t min_ring, double max_zeta_fraction) {
        KcFitOptions options;
        options.form = heightmap::parse_form(form, "form");
        options.min_ring = min_ring;
        options.max_nyquist_fraction = max_zeta_fraction;
        return options;
    };

    m.def(
        "fit_elliptical",
        [fit_options](const heightmap::HeightMap& map, const std::string& form, std::size_t min_ring, double max_zeta_fraction) {
            const KcFitOptions options = fit_options(form, min_ring, max_zeta_fraction);
            py::gil_scoped_release release;
            EllipticalKcFit fit = fit_surface(map, options).elliptical;
            require_resolved(fit);
            return fit;
        },
        py::arg("height_map"), py::arg("form") = "plane", py::arg("min_ring") = KcFitOptions{}.min_ring,
        py::arg("max_zeta_fraction") = KcFitOptions{}.max_nyquist_fraction,
        "Fits an elliptical K-correlation PSD to a HeightMap's 2-D periodogram in the band of fit_surface (started "
        "from its fit, resolved or not): an EllipticalFit. Error if the elliptical fit does not resolve LU, LV or "
        "gamma.");

    m.def(
        "fit_surface",
        [fit_options](const heightmap::HeightMap& map, const std::string& form, std::size_t min_ring, double max_zeta_fraction) {
            const KcFitOptions options = fit_options(form, min_ring, max_zeta_fraction);
            py::gil_scoped_release release;
            SurfaceFit fit = fit_surface(map, options);
            require_resolved(fit.kc);
            return fit;
        },
        py::arg("height_map"), py::arg("form") = "plane", py::arg("min_ring") = KcFitOptions{}.min_ring,
        py::arg("max_zeta_fraction") = KcFitOptions{}.max_nyquist_fraction,
        "Fits a K-correlation PSD to a HeightMap (kc_fit.hpp): weighted log least squares over the rings of the "
        "Hann periodogram from ring min_ring to max_zeta_fraction of Nyquist, after removing `form`. A SurfaceFit "
        "(as `surfscatter surface fit --min-ring --max-zeta-fraction --form`). Error if the map does not resolve "
        "the correlation length or gamma.");
}

}  // namespace

void bind_surface(py::module_& m) {
    bind_statistics(m);
    bind_height_maps(m);
}

}  // namespace surfscatter::python
