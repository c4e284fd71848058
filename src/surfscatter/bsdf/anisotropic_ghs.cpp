#include "surfscatter/bsdf/anisotropic_ghs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::bsdf {

namespace {

const NodeAxis kIncidenceAxis = ghs_incidence_axis();
const NodeAxis kWavelengthAxis = ghs_wavelength_axis();
constexpr int kLastAzimuth = AnisotropicGhsBsdf::kAzimuthNodes - 1;

// cos 2 phi_r of incidence wi: (u^2 - v^2) / (u^2 + v^2) of its lay components; 1 at normal incidence (where every
// azimuth node holds the same values).
double azimuth_coordinate(Vec2 uv) {
    const double u2 = uv.x * uv.x, v2 = uv.y * uv.y, r2 = u2 + v2;
    return r2 > 0 ? (u2 - v2) / r2 : 1.0;
}

}  // namespace

AnisotropicGhsBsdf::AnisotropicGhsBsdf(std::shared_ptr<const surface::EllipticalStatistics> stats,
                                       std::shared_ptr<const ScatterCore> core, material::Conductor material,
                                       GhsSettings settings)
    : stats_(std::move(stats)), core_(std::move(core)), material_(std::move(material)),
      settings_(std::move(settings)), tables_(std::size_t(kWavelengthAxis.size())) {
    if (!stats_ || !core_) fail("anisotropic {} needs elliptical statistics and a scatter core", settings_.name);
    if (stats_->radial().psd_jump_radius() != 0)
        fail("anisotropic {} needs a PSD without a jump (the stretched jump is an ellipse)", settings_.name);
    stretch_ = stats_->stretch();
    stretch2_ = stretch_ * stretch_;
    const auto* exact = dynamic_cast<const ExactScatterCore*>(core_.get());
    log_native_ = exact ? &exact->table() : nullptr;
}

[[gnu::always_inline]] inline AnisotropicGhsBsdf::Incidence AnisotropicGhsBsdf::lookup(const Vec3& wi,
                                                                                        double lambda_nm,
                                                                                        double k) const {
    if (!(lambda_nm >= kGhsMinWavelength && lambda_nm <= kGhsMaxWavelength)) ghs_wavelength_out_of_range(lambda_nm);
    const NodeAxis::Position l = kWavelengthAxis.position(lambda_nm);
    const double cosine = std::clamp(wi.z, kIncidenceAxis.node(0), 1.0);
    const int c = kIncidenceAxis.position(cosine).interval;
    const math::Pair d = math::Pair{1.0, 1.0} * (cosine - kIncidenceAxis.node(c));
    // Azimuth: the 4 uniform nodes around x = (cos 2 phi_r + 1) / h (one-sided at the ends), Lagrange weights at t.
    double x = 0.5 * kLastAzimuth * (azimuth_coordinate(stats_->to_lay({wi.x, wi.y})) + 1.0);
    if (!(x >= 0.0)) x = 0.0;
    x = std::min(x, double(kLastAzimuth));
    const int first = std::clamp(int(x) - 1, 0, kLastAzimuth - 3);
    const double t = x - first;
    const double w[4] = {-(t - 1) * (t - 2) * (t - 3) / 6, t * (t - 2) * (t - 3) / 2, -t * (t - 1) * (t - 3) / 2,
                         t * (t - 1) * (t - 2) / 6};
    auto table = [&](int slot) -> const AzimuthTables& {
        return tables_.get(std::size_t(slot), [&] { return cached_tables(kWavelengthAxis.node(slot)); });
    };
    auto at = [&](const AzimuthTables& tables) {
        math::Pair v{0.0, 0.0};
        for (int j = 0; j < 4; ++j) v += w[j] * estrin(tables[std::size_t(first + j)][std::size_t(c)], d);
        return v;
    };
    const math::Pair at_a = at(table(l.interval)), v = at_a + l.t * (at(table(l.interval + 1)) - at_a);
    return {k, v[0], v[1]};
}

AnisotropicGhsBsdf::Incidence AnisotropicGhsBsdf::lookup(const Vec3& wi, double lambda_nm) const {
    return lookup(wi, lambda_nm, wavenumber(lambda_nm));
}

namespace {
double specular_exponent(double k, double log_sigma, double cos_theta_i) {
    const double a = 2.0 * k * cos_theta_i;
    return a * a * math::fast_exp(2.0 * log_sigma);
}
}  // namespace

double AnisotropicGhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    const double r = stretched(wi.x + wo.x, wi.y + wo.y);
    return eval(wi, wo, lambda_nm, lookup(wi, lambda_nm, k), 2.0 * math::fast_log(k * (wi.z + wo.z)),
                0.5 * math::fast_log(k * k * r * r));
}

// log_g_over_sigma2 = 2 ln(k (cos i + cos o)), log_zeta = ln(k |(zeta_u, s zeta_v)| / k)).
[[gnu::always_inline]] inline double AnisotropicGhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm,
                                                              const Incidence& in, double log_g_over_sigma2,
                                                              double log_zeta) const {
    const double k = in.k;
    const double scale = lobe_fresnel(material_, settings_.fresnel, wi, wo, lambda_nm) * norm_power(wi.z) * k * k *
                         stretch_;
    const double log_g = log_g_over_sigma2 + 2.0 * in.log_sigma;
    const double f = log_native_ ? scale * math::fast_exp(in.log_norm + log_native_->log_eval_at_logs(log_g, log_zeta))
                                 : scale * math::fast_exp(in.log_norm) * core_->density_at_logs(log_g, log_zeta);
    return std::isfinite(f) ? f : 0.0;
}

WavelengthValues AnisotropicGhsBsdf::eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                                 WavelengthValues* pdf) const {
    WavelengthValues f{};
    if (pdf) pdf->fill(0.0);
    if (wi.z <= 0 || wo.z <= 0) return f;
    const double r = stretched(wi.x + wo.x, wi.y + wo.y);
    const double log_cosine_sum = math::fast_log(wi.z + wo.z), log_r = 0.5 * math::fast_log(r * r);
    for (std::size_t j = 0; j < f.size(); ++j) {
        const double k = wavenumber(lambda_nm[j]), log_k = math::fast_log(k);
        f[j] = eval(wi, wo, lambda_nm[j], lookup(wi, lambda_nm[j], k), 2.0 * (log_k + log_cosine_sum), log_k + log_r);
        if (pdf) (*pdf)[j] = this->pdf(wo, wi, lookup(wo, lambda_nm[j], k));
    }
    return f;
}

double AnisotropicGhsBsdf::delta_probability(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    const Incidence in = lookup(wi, lambda_nm);
    return std::exp(-specular_exponent(in.k, in.log_sigma, wi.z));
}

double AnisotropicGhsBsdf::delta_reflectance(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    return material_.reflectance(std::min(1.0, wi.z), lambda_nm) * delta_probability(wi, lambda_nm);
}

// Every stretched radius of the visible disc is below k (1 + sin theta_i) max(1, s).
double AnisotropicGhsBsdf::stretched_zeta_max(const Vec3& wi, double k) const {
    return k * (1.0 + sin_theta(wi)) * std::max(1.0, stretch_);
}

double AnisotropicGhsBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return pdf(wi, wo, lookup(wi, lambda_nm));
}

// d^2 w = s d^2 zeta = s k^2 cos theta_o d omega.
double AnisotropicGhsBsdf::pdf(const Vec3& wi, const Vec3& wo, const Incidence& in) const {
    const double k = in.k, g0 = specular_exponent(k, in.log_sigma, wi.z);
    const double w = k * stretched(wi.x + wo.x, wi.y + wo.y);
    const double p = math::one_minus_exp(g0) * stretch_ * k * k * wo.z *
                     core_->sample_density(g0, stretched_zeta_max(wi, k), w);
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> AnisotropicGhsBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const Incidence in = lookup(wi, lambda_nm);
    const double k = in.k, g0 = specular_exponent(k, in.log_sigma, wi.z);
    const double p_delta = std::exp(-g0);
    if (u_lobe < p_delta) return coherent_delta_sample(material_, wi, lambda_nm, p_delta);
    BsdfSample out;
    const double u_order = std::min((u_lobe - p_delta) / (1.0 - p_delta), std::nextafter(1.0, 0.0));
    const double radius = core_->sample_radius(g0, stretched_zeta_max(wi, k), u_order, u.x) / k;
    const double psi = kTwoPi * u.y;
    const Vec2 q = stats_->from_lay({radius * std::cos(psi), radius * std::sin(psi) / stretch_});  // i_xy + o_xy
    const double ox = q.x - wi.x, oy = q.y - wi.y, z2 = 1.0 - ox * ox - oy * oy;
    if (!(z2 > 0)) return std::nullopt;  // outside the visible disc: a failed sample (the pdf's missing mass)
    out.wo = Vec3(ox, oy, std::sqrt(z2));
    out.pdf = pdf(wi, out.wo, in);
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    const double r = stretched(q.x, q.y);
    out.weight = eval(wi, out.wo, lambda_nm, in, 2.0 * math::fast_log(k * (wi.z + out.wo.z)),
                      0.5 * math::fast_log(k * k * r * r)) * out.wo.z / out.pdf;
    if (!std::isfinite(out.weight)) return std::nullopt;
    return out;
}

AnisotropicGhsBsdf::AzimuthTables AnisotropicGhsBsdf::cached_tables(double lambda_nm) const {
    constexpr std::uint32_t kVersion = 1;  // of build_tables' construction and the layout
    const std::string key = fmt::format(
        "ghs-anisotropic-incidence:{}:sigma_h={:.17g}:{}:normalization={}:relevant={}:lambda={:.17g}:nodes={}x{}"
        ":azimuth=cos2(phi-A)",
        stats_->cache_key(), stats_->sigma_h(), core_->cache_key(), int(settings_.normalization),
        settings_.relevant_roughness, lambda_nm, kGhsThetaNodes, kAzimuthNodes);
    return cached_incidence_table<AzimuthTables>("ghs-anisotropic-incidence", kVersion, key,
                                                 [&] { return build_tables(lambda_nm); });
}

AnisotropicGhsBsdf::AzimuthTables AnisotropicGhsBsdf::build_tables(double lambda_nm) const {
    AzimuthTables tables;
    std::array<double, kGhsThetaNodes> x{}, log_sigma{}, log_norm{};
    for (int a = 0; a < kAzimuthNodes; ++a) {
        const double phi_r = 0.5 * std::acos(std::clamp(-1.0 + 2.0 * a / kLastAzimuth, -1.0, 1.0));
        const Vec2 along = stats_->from_lay({std::cos(phi_r), std::sin(phi_r)});
        for (int j = 0; j < kGhsThetaNodes; ++j) {
            x[j] = kIncidenceAxis.node(j);
            const double s = std::sqrt(std::max(0.0, 1.0 - x[j] * x[j]));
            const GhsBsdf::Direct d = direct(Vec3(s * along.x, s * along.y, x[j]), lambda_nm);
            // Finite logarithms even for sigma = 0 or N = 0, for the interpolation.
            log_sigma[j] = std::log(std::max(d.sigma, std::numeric_limits<double>::min()));
            log_norm[j] = std::log(std::max(d.norm / norm_power(x[j]), std::numeric_limits<double>::min()));
        }
        tables[std::size_t(a)] = fit_incidence_table(x, log_sigma, log_norm);
    }
    return tables;
}

double AnisotropicGhsBsdf::disc_integral(const Vec3& wi, const std::function<double(Vec2, double)>& f) const {
    const double s = sin_theta(wi);
    // The lay components of q = q (cos(phi_i + phi), sin(phi_i + phi)) and of its mirror image phi -> -phi, from
    // cos phi and sin phi alone.
    const Vec2 along = s > 0 ? stats_->to_lay({wi.x / s, wi.y / s}) : stats_->to_lay({1.0, 0.0});
    return integrate_disc_adaptive(s, wi.z, [&](double q, double phi, double cos2_theta_o) {
        const double c = q * std::cos(phi), t = q * std::sin(phi);
        const double uc = along.x * c, us = along.x * t, vc = along.y * c, vs = along.y * t;
        return 0.5 * (f({uc - vs, vc + us}, cos2_theta_o) + f({uc + vs, vc - us}, cos2_theta_o));
    }, 1e-4).value;
}

// Along rays zeta = t e from the specular point (|e| = 1, at azimuth phi from the incidence plane): the ray leaves the
// visible disc at t = k q_max, q_max = b + sqrt(b^2 + cos^2 theta_i), b = sin theta_i cos phi, and P-hat(t e) =
// s P-hat_radial(a t), a = |(e_u, s e_v)|, so it carries s / (2 pi a^2) F(a k q_max), F the radial CDF (closed form for
// KC and Gaussian): a 1-D integral over phi, split where b = 0 (at grazing incidence q_max falls from 2 to 0 there).
double AnisotropicGhsBsdf::visible_disc_mass(const Vec3& wi, double k) const {
    const double s = sin_theta(wi), c2 = wi.z * wi.z, phi_i = s > 0 ? std::atan2(wi.y, wi.x) : 0.0;
    auto ray = [&](double phi) {
        const double b = s * std::cos(phi), root = std::sqrt(b * b + c2);
        const double q_max = b >= 0 ? b + root : c2 / (root - b);  // no cancellation for b < 0
        const Vec2 uv = stats_->to_lay({std::cos(phi_i + phi), std::sin(phi_i + phi)});
        const double a2 = uv.x * uv.x + stretch2_ * uv.y * uv.y;
        return stretch_ / (kTwoPi * a2) * stats_->radial().radial_cdf(std::sqrt(a2) * k * q_max);
    };
    double mass = 0;
    for (int quarter = 0; quarter < 4; ++quarter)
        mass += math::integrate_adaptive(ray, 0.5 * kPi * quarter, 0.5 * kPi * (quarter + 1), 1e-10, 1e-14);
    return std::clamp(mass, 0.0, 1.0);
}

GhsBsdf::Direct AnisotropicGhsBsdf::direct(const Vec3& wi, double lambda_nm) const {
    const double k = wavenumber(lambda_nm), ci = wi.z;
    const bool needs_mass = settings_.relevant_roughness || settings_.normalization == LobeNormalization::disc_mass;
    const double disc_mass = needs_mass ? visible_disc_mass(wi, k) : 1.0;
    const double sigma = settings_.relevant_roughness ? stats_->sigma_h() * std::sqrt(disc_mass) : stats_->sigma_h();
    switch (settings_.normalization) {
        case LobeNormalization::none: return {sigma, 1.0};
        case LobeNormalization::disc_mass: return {sigma, 1.0 / disc_mass};
        case LobeNormalization::albedo: {
            const double a = 2.0 * k * sigma * ci;
            const double mass = k * k * stretch_ * disc_integral(wi, [&](Vec2 uv, double cos2_theta_o) {
                return core_->density_at_logs(2.0 * math::fast_log(k * sigma * (ci + std::sqrt(cos2_theta_o))),
                                              0.5 * math::fast_log(k * k * (uv.x * uv.x + stretch2_ * uv.y * uv.y)));
            });
            return {sigma, mass > 0 ? -std::expm1(-a * a) / mass : 1.0};
        }
    }
    return {sigma, 1.0};
}

}  // namespace surfscatter::bsdf
