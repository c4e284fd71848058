#include "surfscatter/bsdf/rgl_measured.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/rgb_to_spectrum.hpp"

namespace surfscatter::bsdf {

namespace {

using io::TensorDtype;
using io::TensorField;

// RGB files become spectra on this grid (the renderer's range, 5 nm: the CIE tables' own spacing).
constexpr double kRgbLambdaMin = 360.0, kRgbLambdaStep = 5.0;
constexpr int kRgbLambdaCount = 95;

const TensorField& field(const io::TensorFile& file, const std::string& name, TensorDtype dtype, std::size_t rank,
                         const std::string& origin) {
    const TensorField& f = file.at(name, origin);
    if (f.dtype != dtype || f.shape.size() != rank)
        fail("RGL file {}: field '{}' is {} of rank {}, expected {} of rank {}", printable(origin, kShownPathChars), name,
             io::dtype_name(f.dtype), f.shape.size(), io::dtype_name(dtype), rank);
    return f;
}

std::vector<double> finite_values(const TensorField& f, const std::string& origin, bool non_negative) {
    std::vector<double> v = f.values();
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]) || (non_negative && v[i] < 0))
            fail("RGL file {}: field '{}' holds {} at element {}", printable(origin, kShownPathChars), f.name, v[i], i);
    return v;
}

std::vector<float> to_floats(const std::vector<double>& v) { return {v.begin(), v.end()}; }

// Mitsuba's mulsign_neg: x times minus the sign of s (+0 counts as positive).
double flip(double x, double s) { return s >= 0 ? -x : x; }

}  // namespace

double rgl_theta_to_u(double theta) { return std::sqrt(std::max(0.0, theta) * (2.0 / kPi)); }
double rgl_u_to_theta(double u) { return u * u * (kPi / 2.0); }
double rgl_phi_to_u(double phi) { return (phi + kPi) / kTwoPi; }
double rgl_u_to_phi(double u) { return (2.0 * u - 1.0) * kPi; }
double rgl_elevation(const Vec3& w) {
    const double dist = std::sqrt(w.x * w.x + w.y * w.y + (w.z - 1) * (w.z - 1));
    return 2.0 * std::asin(std::min(1.0, 0.5 * dist));
}

RglData rgl_from_tensor(const io::TensorFile& file, const std::string& origin) {
    const std::string shown = printable(origin, kShownPathChars);
    RglData d;
    const auto& description = field(file, "description", TensorDtype::UInt8, 1, origin);
    d.description = description.bytes;
    if (const TensorField* version = file.find("version"); version && version->element_count() == 2) {
        const auto v = version->values();
        d.version[0] = static_cast<std::uint32_t>(v[0]);
        d.version[1] = static_cast<std::uint32_t>(v[1]);
    }
    const auto& theta_i = field(file, "theta_i", TensorDtype::Float32, 1, origin);
    const auto& phi_i = field(file, "phi_i", TensorDtype::Float32, 1, origin);
    const auto& ndf = field(file, "ndf", TensorDtype::Float32, 2, origin);
    const auto& sigma = field(file, "sigma", TensorDtype::Float32, 2, origin);
    const auto& vndf = field(file, "vndf", TensorDtype::Float32, 4, origin);
    const auto& luminance = field(file, "luminance", TensorDtype::Float32, 4, origin);
    const auto& jacobian = field(file, "jacobian", TensorDtype::UInt8, 1, origin);
    const std::uint64_t n_phi = phi_i.shape[0], n_theta = theta_i.shape[0];
    auto require = [&](bool ok, const char* what) {
        if (!ok) fail("RGL file {}: {}", shown, what);
    };
    require(n_phi >= 1 && n_theta >= 2, "phi_i needs >= 1 and theta_i >= 2 values");
    require(jacobian.shape[0] == 1, "jacobian must hold one value");
    require(vndf.shape[0] == n_phi && vndf.shape[1] == n_theta, "vndf shape does not match phi_i x theta_i");
    require(luminance.shape[0] == n_phi && luminance.shape[1] == n_theta,
            "luminance shape does not match phi_i x theta_i");
    require(luminance.shape[2] == luminance.shape[3], "luminance is not square");
    d.theta_i = finite_values(theta_i, origin, false);
    d.phi_i = finite_values(phi_i, origin, false);
    d.jacobian = jacobian.bytes[0] != 0;
    d.ndf_rows = ndf.shape[0], d.ndf_cols = ndf.shape[1];
    d.sigma_rows = sigma.shape[0], d.sigma_cols = sigma.shape[1];
    d.ndf = finite_values(ndf, origin, true);
    d.sigma = finite_values(sigma, origin, true);
    if (d.jacobian)
        for (double s : d.sigma) require(s > 0, "sigma (projected area) must be > 0 everywhere");
    d.vndf_rows = vndf.shape[2], d.vndf_cols = vndf.shape[3];
    d.vndf = finite_values(vndf, origin, true);
    d.rows = luminance.shape[2], d.cols = luminance.shape[3];
    d.luminance = finite_values(luminance, origin, true);
    const TensorField* spectra = file.find("spectra");
    const TensorField* rgb = file.find("rgb");
    if (spectra) {
        const auto& s = field(file, "spectra", TensorDtype::Float32, 5, origin);
        const auto& w = field(file, "wavelengths", TensorDtype::Float32, 1, origin);
        require(s.shape[0] == n_phi && s.shape[1] == n_theta && s.shape[2] == w.shape[0] && s.shape[3] == d.rows &&
                    s.shape[4] == d.cols,
                "spectra shape does not match phi_i x theta_i x wavelengths x luminance");
        d.wavelengths = finite_values(w, origin, true);
        d.spectra = finite_values(s, origin, false);
        require(d.wavelengths.size() >= 2, "wavelengths needs >= 2 values");
    } else if (rgb) {
        const auto& s = field(file, "rgb", TensorDtype::Float32, 5, origin);
        require(s.shape[0] == n_phi && s.shape[1] == n_theta && s.shape[2] == 3 && s.shape[3] == d.rows &&
                    s.shape[4] == d.cols,
                "rgb shape does not match phi_i x theta_i x 3 x luminance");
        d.rgb = true;
        d.spectra = finite_values(s, origin, false);
    } else {
        fail("RGL file {}: neither 'spectra' nor 'rgb' field", shown);
    }
    if (const TensorField* valid = file.find("valid")) d.valid = valid->bytes;
    for (std::size_t k = 1; k < d.theta_i.size(); ++k) require(d.theta_i[k] > d.theta_i[k - 1], "theta_i must increase");
    for (std::size_t k = 1; k < d.phi_i.size(); ++k) require(d.phi_i[k] > d.phi_i[k - 1], "phi_i must increase");
    return d;
}

io::TensorFile rgl_to_tensor(const RglData& d) {
    using io::TensorField;
    auto u64 = [](std::size_t x) { return static_cast<std::uint64_t>(x); };
    io::TensorFile f;
    std::string version(8, '\0');
    std::memcpy(version.data(), d.version, 8);
    f.fields.push_back(TensorField::of_bytes("version", TensorDtype::UInt32, {2}, version));
    f.fields.push_back(TensorField::of_bytes("description", TensorDtype::UInt8, {u64(d.description.size())},
                                             d.description));
    f.fields.push_back(TensorField::of_bytes("jacobian", TensorDtype::UInt8, {1}, std::string(1, d.jacobian ? 1 : 0)));
    f.fields.push_back(TensorField::of_floats("theta_i", {u64(d.theta_i.size())}, to_floats(d.theta_i)));
    f.fields.push_back(TensorField::of_floats("phi_i", {u64(d.phi_i.size())}, to_floats(d.phi_i)));
    f.fields.push_back(TensorField::of_floats("ndf", {u64(d.ndf_rows), u64(d.ndf_cols)}, to_floats(d.ndf)));
    f.fields.push_back(TensorField::of_floats("sigma", {u64(d.sigma_rows), u64(d.sigma_cols)}, to_floats(d.sigma)));
    const std::uint64_t np = d.phi_i.size(), nt = d.theta_i.size();
    f.fields.push_back(TensorField::of_floats("vndf", {np, nt, u64(d.vndf_rows), u64(d.vndf_cols)}, to_floats(d.vndf)));
    f.fields.push_back(TensorField::of_floats("luminance", {np, nt, u64(d.rows), u64(d.cols)}, to_floats(d.luminance)));
    if (d.rgb) {
        f.fields.push_back(TensorField::of_floats("rgb", {np, nt, 3, u64(d.rows), u64(d.cols)}, to_floats(d.spectra)));
    } else {
        f.fields.push_back(TensorField::of_floats("wavelengths", {u64(d.wavelengths.size())}, to_floats(d.wavelengths)));
        f.fields.push_back(TensorField::of_floats("spectra", {np, nt, u64(d.wavelengths.size()), u64(d.rows), u64(d.cols)},
                                                  to_floats(d.spectra)));
    }
    if (!d.valid.empty()) f.fields.push_back(TensorField::of_bytes("valid", TensorDtype::UInt8, {u64(d.valid.size())}, d.valid));
    return f;
}

RglData read_rgl(const std::filesystem::path& path) {
    return rgl_from_tensor(io::read_tensor_file(path), path.string());
}

void write_rgl(const std::filesystem::path& path, const RglData& data) { io::write_tensor_file(path, rgl_to_tensor(data)); }

RglMeasuredBsdf::RglMeasuredBsdf(const RglData& d, std::string name)
    : name_(std::move(name)), isotropic_(d.isotropic()), jacobian_(d.jacobian) {
    if (!isotropic_) {
        const double span = d.phi_i.back() - d.phi_i.front();
        reduction_ = static_cast<int>(std::lround(kTwoPi / span));
        if (reduction_ != 1 && reduction_ != 2 && reduction_ != 4)
            fail("RGL file '{}': phi_i spans {} rad, not 2 pi, pi or pi / 2", printable(d.description), span);
    }
    ndf_ = Marginal2D(d.ndf, d.ndf_cols, d.ndf_rows, {}, false);
    sigma_ = Marginal2D(d.sigma, d.sigma_cols, d.sigma_rows, {}, false);
    vndf_ = Marginal2D(d.vndf, d.vndf_cols, d.vndf_rows, {d.phi_i, d.theta_i}, true);
    luminance_ = Marginal2D(d.luminance, d.cols, d.rows, {d.phi_i, d.theta_i}, true);
    if (!d.rgb) {
        wavelengths_ = d.wavelengths;
        std::vector<double> s = d.spectra;
        for (double& v : s) v = std::max(v, 0.0);  // a measurement's noise may dip below 0; f is max(0, .) anyway
        spectra_ = Marginal2D(s, d.cols, d.rows, {d.phi_i, d.theta_i, wavelengths_}, false);
        return;
    }
    wavelengths_.resize(kRgbLambdaCount);
    for (int k = 0; k < kRgbLambdaCount; ++k) wavelengths_[static_cast<std::size_t>(k)] = kRgbLambdaMin + kRgbLambdaStep * k;
    const std::size_t plane = d.rows * d.cols, slices = d.phi_i.size() * d.theta_i.size();
    std::vector<double> s(slices * kRgbLambdaCount * plane, 0.0);
    for (std::size_t slice = 0; slice < slices; ++slice)
        for (std::size_t i = 0; i < plane; ++i) {
            std::array<double, 3> c{};
            for (std::size_t ch = 0; ch < 3; ++ch) c[ch] = std::max(0.0, d.spectra[(slice * 3 + ch) * plane + i]);
            const double scale = std::max({c[0], c[1], c[2]});
            if (!(scale > 0)) continue;
            for (double& x : c) x /= scale;
            const spectrum::RgbSigmoid sigmoid = spectrum::fit_rgb_sigmoid(c);
            for (std::size_t k = 0; k < wavelengths_.size(); ++k)
                s[(slice * wavelengths_.size() + k) * plane + i] = scale * sigmoid(wavelengths_[k]);
        }
    spectra_ = Marginal2D(s, d.cols, d.rows, {d.phi_i, d.theta_i, wavelengths_}, false);
}

void RglMeasuredBsdf::check_lambda(double lambda_nm) const {
    if (!(lambda_nm >= wavelengths_.front() && lambda_nm <= wavelengths_.back()))
        fail("measured BSDF '{}': wavelength {} nm outside its table ({}-{} nm)", printable(name_), lambda_nm,
             wavelengths_.front(), wavelengths_.back());
}

RglMeasuredBsdf::Frame RglMeasuredBsdf::fold(const Vec3& wi) const {
    Frame f{wi, 1, 1};
    if (reduction_ >= 2) {
        f.sy = flip(1.0, wi.y);
        f.sx = reduction_ == 4 ? flip(1.0, wi.x) : f.sy;
        f.wi.x *= f.sx;
        f.wi.y *= f.sy;
    }
    return f;
}

double RglMeasuredBsdf::table_value(Vec2 sample, double phi_i, double theta_i, double lambda_nm) const {
    const double params[3] = {phi_i, theta_i, lambda_nm};
    return std::max(0.0, spectra_.eval(sample, params));
}

RglMeasuredBsdf::Lookup RglMeasuredBsdf::lookup(const Vec3& wi_, const Vec3& wo_) const {
    const Frame fr = fold(wi_);
    const Vec3 wi = fr.wi, wo{wo_.x * fr.sx, wo_.y * fr.sy, wo_.z};
    const Vec3 m = normalize(wi + wo);
    const double theta_i = rgl_elevation(wi), phi_i = std::atan2(wi.y, wi.x);
    const double theta_m = rgl_elevation(m), phi_m = std::atan2(m.y, m.x);
    Vec2 u_m{rgl_theta_to_u(theta_m), rgl_phi_to_u(isotropic_ ? phi_m - phi_i : phi_m)};
    u_m.y -= std::floor(u_m.y);
    return {wi, m, u_m, {phi_i, theta_i}};
}

double RglMeasuredBsdf::eval(const Vec3& wi_, const Vec3& wo_, double lambda_nm) const {
    check_lambda(lambda_nm);
    if (wi_.z <= 0 || wo_.z <= 0) return 0.0;
    const Lookup l = lookup(wi_, wo_);
    const double phi_i = l.params[0], theta_i = l.params[1];
    const Vec2 sample = vndf_.invert(l.u_m, l.params).first;
    double v = table_value(sample, phi_i, theta_i, lambda_nm);
    if (jacobian_) v *= ndf_.eval(l.u_m) / (4 * sigma_.eval({rgl_theta_to_u(theta_i), rgl_phi_to_u(phi_i)}));
    return v / wo_.z;
}

double RglMeasuredBsdf::pdf(const Vec3& wi_, const Vec3& wo_, double /*lambda_nm*/) const {
    if (wi_.z <= 0 || wo_.z <= 0) return 0.0;
    const Lookup l = lookup(wi_, wo_);
    const auto [sample, vndf_pdf] = vndf_.invert(l.u_m, l.params);
    const double luminance_pdf = luminance_.eval(sample, l.params);
    const double jacobian = std::max(2 * kPi * kPi * l.u_m.x * sin_theta(l.m), 1e-6) * 4 * dot(l.wi, l.m);
    const double p = vndf_pdf * luminance_pdf / jacobian;
    return p > 0 && std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> RglMeasuredBsdf::sample(const Vec3& wi_, double lambda_nm, double /*u_lobe*/, Vec2 u) const {
    check_lambda(lambda_nm);
    if (wi_.z <= 0) return std::nullopt;
    const Frame fr = fold(wi_);
    const Vec3 wi = fr.wi;
    const double theta_i = rgl_elevation(wi), phi_i = std::atan2(wi.y, wi.x);
    const double params[2] = {phi_i, theta_i};
    const auto [s, luminance_pdf] = luminance_.sample({u.y, u.x}, params);
    const auto [u_m, vndf_pdf] = vndf_.sample(s, params);
    const double theta_m = rgl_u_to_theta(u_m.x);
    const double phi_m = rgl_u_to_phi(u_m.y) + (isotropic_ ? phi_i : 0.0);
    const Vec3 m = spherical_direction(theta_m, phi_m);
    const double wi_m = dot(wi, m);
    if (!(wi_m > 0)) return std::nullopt;
    const double jacobian = std::max(2 * kPi * kPi * u_m.x * std::sin(theta_m), 1e-6) * 4 * wi_m;
    const Vec3 wo_folded = m * (2 * wi_m) - wi;
    BsdfSample out;
    out.wo = normalize(Vec3{wo_folded.x * fr.sx, wo_folded.y * fr.sy, wo_folded.z});
    if (out.wo.z <= 0) return std::nullopt;
    out.pdf = vndf_pdf * luminance_pdf / jacobian;
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    out.weight = eval(wi_, out.wo, lambda_nm) * out.wo.z / out.pdf;
    return out;
}

}  // namespace surfscatter::bsdf
