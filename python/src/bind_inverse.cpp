// surfscatter.fit_brdf: each model's surface statistics fitted to a measured BRDF (inverse/fit_brdf.hpp), as
// `surfscatter fit-brdf`; the result is the CLI's JSON document as a dict, with each model's fit and residual per
// row as numpy arrays.
#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/inverse/brdf_data.hpp"
#include "surfscatter/inverse/fit_report.hpp"

namespace surfscatter::python {

using namespace pybind11::literals;

namespace {

// A 1-D float64 column of the data dict, by name ("data['brdf']").
std::vector<double> column(const py::dict& data, const char* name) {
    if (!data.contains(name)) fail("data has no '{}' (the columns of docs/FIT.md)", name);
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(data[name]);
    if (!a || a.ndim() != 1) fail("data['{}'] must be a 1-D array of numbers", name);
    return std::vector<double>(a.data(), a.data() + a.size());
}

inverse::BrdfData data_of(const py::handle& data, const std::optional<std::vector<double>>& wavelengths_nm) {
    if (!py::isinstance<py::dict>(data)) {
        const std::string path = path_string(data, "data");
        if (std::filesystem::path(path).extension() == ".bsdf")
            return inverse::read_brdf_rgl(path, wavelengths_nm.value_or(std::vector<double>{450, 550, 650}));
        if (wavelengths_nm) fail("wavelengths_nm applies to RGL .bsdf data only (a CSV names its own)");
        return inverse::read_brdf_csv(path);
    }
    if (wavelengths_nm) fail("wavelengths_nm applies to RGL .bsdf data only (a dict names its own)");
    const py::dict d = py::reinterpret_borrow<py::dict>(data);
    static const char* kNames[] = {"wavelength_nm", "theta_i_deg", "phi_i_deg", "theta_o_deg", "phi_o_deg", "brdf",
                                   "brdf_stderr"};
    for (const auto& [key, value] : d) {
        const std::string k = py::str(key).cast<std::string>();
        if (std::find_if(std::begin(kNames), std::end(kNames), [&](const char* n) { return k == n; }) == std::end(kNames))
            fail("data['{}'] is not a column of a BRDF measurement (docs/FIT.md)", printable(k));
    }
    inverse::BrdfData b;
    b.source = "data";
    b.wavelength_nm = column(d, "wavelength_nm");
    b.theta_i_deg = column(d, "theta_i_deg");
    b.phi_i_deg = column(d, "phi_i_deg");
    b.theta_o_deg = column(d, "theta_o_deg");
    b.phi_o_deg = column(d, "phi_o_deg");
    b.brdf = column(d, "brdf");
    if (d.contains("brdf_stderr")) b.brdf_stderr = column(d, "brdf_stderr");
    inverse::validate(b);
    return b;
}

py::dict fit_brdf(const py::handle& data, const std::string& material, const std::vector<std::string>& models,
                  const std::string& psd, bool anisotropic, const std::map<std::string, double>& fix,
                  const std::optional<std::vector<double>>& wavelengths_nm, const std::optional<std::string>& profile) {
    const inverse::BrdfData brdf = data_of(data, wavelengths_nm);
    inverse::FitOptions options;
    options.names = {.fix = "fix", .psd = "psd", .anisotropic = "anisotropic", .profile = "profile"};
    options.material = material;
    options.psd = bsdf::parse_psd(psd, "psd");
    options.anisotropic = anisotropic;
    options.fixed = fix;
    if (profile) {
        if (!py::isinstance<py::dict>(data) && std::filesystem::path(path_string(data, "data")).extension() == ".bsdf")
            fail("profile applies to data of a profile (1-D), not to an RGL .bsdf file");
        options.profile = bsdf::parse_profile_polarisation(*profile, "profile");
    }
    if (!models.empty()) {
        options.models.clear();
        for (const std::string& m : models) options.models.push_back(bsdf::parse_model(m, "models"));
    }
    inverse::FitResult result;
    {
        py::gil_scoped_release release;
        result = inverse::fit_brdf(brdf, options);
    }
    const std::string text = inverse::fit_json(brdf, options, result).dump();
    py::dict out = py::module_::import("json").attr("loads")(text);
    py::list fits = out["models"];
    for (std::size_t m = 0; m < result.fits.size(); ++m) {
        py::dict f = fits[m];
        f["fitted"] = py::array_t<double>(static_cast<py::ssize_t>(brdf.size()), result.fits[m].fitted.data());
        f["residual"] = py::array_t<double>(static_cast<py::ssize_t>(brdf.size()), result.fits[m].residual.data());
    }
    return out;
}

}  // namespace

void bind_inverse(py::module_& m) {
    m.def("fit_brdf", &fit_brdf, "data"_a, "material"_a, py::kw_only(),
          "models"_a = std::vector<std::string>{}, "psd"_a = "kc", "anisotropic"_a = false,
          "fix"_a = std::map<std::string, double>{}, "wavelengths_nm"_a = py::none(), "profile"_a = py::none(),
          "Fit each model's surface statistics to a measured BRDF (docs/FIT.md). data: a CSV path, an RGL measured "
          "file (.bsdf: its sample nodes at each incidence, at wavelengths_nm, default 450, 550, 650) or a dict of 1-D "
          "arrays wavelength_nm, theta_i_deg, phi_i_deg, theta_o_deg, phi_o_deg, brdf (1/sr, no cosine) and "
          "optionally brdf_stderr; models: names (default all four); psd: 'kc' or 'gaussian'; fix: "
          "{'gamma': 3, ...}; profile: 's' or 'p' for 1-D data of that polarisation (rows in the plane of incidence, "
          "brdf the scattered power per radian of a profile, as reference exact-1d gives it; the models' 1-D forms). "
          "Returns the dict of `surfscatter fit-brdf`'s JSON, each model with 'fitted' and "
          "'residual' arrays per row.");
}

}  // namespace surfscatter::python
