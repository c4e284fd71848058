#include "surfscatter/bsdf/ghs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/bsdf/incidence_tables.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"

namespace surfscatter::bsdf {

namespace {

const NodeAxis kIncidenceAxis = ghs_incidence_axis();
const NodeAxis kWavelengthAxis = ghs_wavelength_axis();

}  // namespace

GhsBsdf::GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
                 material::Conductor material, GhsSettings settings)
    : stats_(std::move(stats)), core_(std::move(core)), material_(std::move(material)),
      settings_(std::move(settings)), exact_(dynamic_cast<const ExactScatterCore*>(core_.get())),
      log_native_(exact_ && stats_->psd_jump_radius() == 0.0 ? &exact_->table() : nullptr),
      tables_(std::size_t(kWavelengthAxis.size())) {}

[[gnu::always_inline]] inline GhsBsdf::Incidence GhsBsdf::lookup(double cos_theta_i, double lambda_nm,
                                                                  double k) const {
    if (!(lambda_nm >= kMinWavelength && lambda_nm <= kMaxWavelength)) ghs_wavelength_out_of_range(lambda_nm);
    const NodeAxis::Position l = kWavelengthAxis.position(lambda_nm);
    const double cosine = std::clamp(cos_theta_i, kIncidenceAxis.node(0), 1.0);
    const int c = kIncidenceAxis.position(cosine).interval;
    auto table = [&](int slot) -> const Table& {
        return tables_.get(std::size_t(slot), [&] { return cached_table(kWavelengthAxis.node(slot)); });
    };
    const math::Pair d = math::Pair{1.0, 1.0} * (cosine - kIncidenceAxis.node(c));
    const Interval& a = table(l.interval)[c];
    const Interval& b = table(l.interval + 1)[c];
    // Cubic in cos theta_i within each wavelength node's table (lanes: ln sigma, ln N), then linear in lambda.
    const math::Pair at_a = estrin(a, d), v = at_a + l.t * (estrin(b, d) - at_a);
    return {k, v[0], v[1]};
}

GhsBsdf::Incidence GhsBsdf::lookup(double cos_theta_i, double lambda_nm) const {
    return lookup(cos_theta_i, lambda_nm, wavenumber(lambda_nm));
}

double GhsBsdf::core_lobe(const Vec3& wi, const Vec3& wo, double lambda_nm, double sigma_um) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    return k * k * density(LobeLogs(wi, wo, k), std::log(sigma_um));
}

// ln g = 2 ln(k sigma (cos i + cos o)) but for its 2 ln sigma, which the lookup interpolates, and ln zeta,
// zeta = k |i_xy + o_xy|: computed before the lookup, they do not wait for it.
GhsBsdf::LobeLogs::LobeLogs(const Vec3& wi, const Vec3& wo, double k) {
    const double x = wi.x + wo.x, y = wi.y + wo.y;
    log_g_over_sigma2 = 2.0 * math::fast_log(k * (wi.z + wo.z));
    log_zeta = 0.5 * math::fast_log(k * k * (x * x + y * y));
}

// The core's density; the exact core is called without virtual dispatch.
double GhsBsdf::density(const LobeLogs& logs, double log_sigma) const {
    const double log_g = logs.log_g_over_sigma2 + 2.0 * log_sigma;
    return exact_ ? exact_->density_at_logs(log_g, logs.log_zeta) : core_->density_at_logs(log_g, logs.log_zeta);
}


inline double GhsBsdf::fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    return lobe_fresnel(material_, settings_.fresnel, wi, wo, lambda_nm);
}

double GhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    return eval(wi, wo, lambda_nm, lookup(wi.z, lambda_nm, k), LobeLogs(wi, wo, k));
}

double GhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm, const Direct& at) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    const double floor = std::numeric_limits<double>::min();  // as tabulate_incidence: finite logarithms
    const Incidence in{k, std::log(std::max(at.sigma, floor)), std::log(std::max(at.norm / norm_power(wi.z), floor))};
    return eval(wi, wo, lambda_nm, in, LobeLogs(wi, wo, k));
}

// Inlined into its four callers: a call here, and to lookup, cost 20 % of an exact-GHS eval (register saves and
// the Incidence passed through memory).
[[gnu::always_inline]] inline double GhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm,
                                                   const Incidence& in, const LobeLogs& logs) const {
    const double k = in.k;
    const double scale = fresnel(wi, wo, lambda_nm) * norm_power(wi.z) * k * k;
    // The exact core of a PSD without a jump hands ln S_g: one exponential of ln N + ln S_g. Other cores (first order,
    // refit, a high-pass PSD) return the density itself, and exp(ln N) multiplies it (taking its logarithm to add ln N
    // made ghs_ssa eval 1.36x and two_scale eval 1.1-1.17x slower).
    const double f = log_native_ ? scale * math::fast_exp(in.log_norm + log_native_->log_eval_at_logs(
                                                                               logs.log_g_over_sigma2 + 2.0 * in.log_sigma,
                                                                               logs.log_zeta))
                                 : scale * math::fast_exp(in.log_norm) * density(logs, in.log_sigma);
    return std::isfinite(f) ? f : 0.0;
}

WavelengthValues GhsBsdf::eval_packet(const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda_nm,
                                      WavelengthValues* pdf) const {
    WavelengthValues f{};
    if (pdf) pdf->fill(0.0);
    if (wi.z <= 0 || wo.z <= 0) return f;
    const double x = wi.x + wo.x, y = wi.y + wo.y;
    const double log_cosine_sum = math::fast_log(wi.z + wo.z), log_radius2 = math::fast_log(x * x + y * y);
    const Wedge reverse(wo, wi);  // pdf(wo, wi): incidence wo
    for (std::size_t j = 0; j < f.size(); ++j) {
        const double k = wavenumber(lambda_nm[j]);
        f[j] = eval(wi, wo, lambda_nm[j], lookup(wi.z, lambda_nm[j], k),
                    LobeLogs(math::fast_log(k), log_cosine_sum, log_radius2));
        if (pdf) (*pdf)[j] = this->pdf(wo, wi, lookup(wo.z, lambda_nm[j], k), reverse);
    }
    return f;
}

double GhsBsdf::delta_probability(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    return std::exp(-specular_exponent(lookup(wi.z, lambda_nm), wi.z));
}

double GhsBsdf::delta_reflectance(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    return material_.reflectance(std::min(1.0, wi.z), lambda_nm) * delta_probability(wi, lambda_nm);
}

double GhsBsdf::jump_radius(double lambda_nm) const { return stats_->psd_jump_radius() / wavenumber(lambda_nm); }

GhsBsdf::Wedge::Wedge(const Vec3& wi, const Vec3& wo)
    : s(sin_theta(wi)), q(scatter_radius(wi, wo)), phi_max(wedge_half_angle(q, s)) {}

double GhsBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    return pdf(wi, wo, lookup(wi.z, lambda_nm), Wedge(wi, wo));
}

double GhsBsdf::pdf(const Vec3& wi, const Vec3& wo, const Incidence& in, const Wedge& wedge) const {
    const double k = in.k, g0 = specular_exponent(in, wi.z);
    const double zeta_max = k * (1.0 + wedge.s);
    const double p = math::one_minus_exp(g0) *
                     wedge_pdf(k, wo.z, core_->sample_density(g0, zeta_max, k * wedge.q), wedge.phi_max);
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> GhsBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const Incidence in = lookup(wi.z, lambda_nm);
    const double k = in.k, g0 = specular_exponent(in, wi.z);
    const double p_delta = std::exp(-g0);
    if (u_lobe < p_delta) return coherent_delta_sample(material_, wi, lambda_nm, p_delta);
    BsdfSample out;
    const double u_order = std::min((u_lobe - p_delta) / (1.0 - p_delta), std::nextafter(1.0, 0.0));
    const double s = sin_theta(wi);
    const double zeta_max = k * (1.0 + s);
    const double zeta = core_->sample_radius(g0, zeta_max, u_order, u.x);
    const auto wo = wedge_direction(wi, zeta / k, u.y);
    if (!wo) return std::nullopt;
    out.wo = *wo;
    out.pdf = pdf(wi, *wo, in, Wedge(wi, *wo));  // the incidence looked up once for the draw, its pdf and its value
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    out.weight = eval(wi, *wo, lambda_nm, in, LobeLogs(wi, *wo, k)) * wo->z / out.pdf;
    if (!std::isfinite(out.weight)) return std::nullopt;
    return out;
}

// A table takes 64 visible-disc integrals to build (~30 ms; a render touches ~45 wavelength nodes), so it is kept on
// disk beside the lobe tables, under a key naming everything direct() depends on.
GhsBsdf::Table GhsBsdf::cached_table(double lambda_nm) const {
    constexpr std::uint32_t kVersion = 3;  // of build_table's construction and CubicPairInterval's layout
    const std::string key =
        fmt::format("ghs-incidence:{}:sigma_h={:.17g}:{}:normalization={}:relevant={}:lambda={:.17g}:nodes={}",
                    stats_->cache_key(), stats_->sigma_h(), core_->cache_key(), int(settings_.normalization),
                    settings_.relevant_roughness, lambda_nm, kThetaNodes);
    return cached_incidence_table<Table>("ghs-incidence", kVersion, key, [&] { return build_table(lambda_nm); });
}

GhsBsdf::Table GhsBsdf::build_table(double lambda_nm) const {
    return tabulate_incidence(
        kIncidenceAxis, [&](double cos_theta_i) { return direct(std::acos(cos_theta_i), lambda_nm); },
        [this](double c) { return norm_power(c); });
}

GhsBsdf::Direct GhsBsdf::direct(double theta_i, double lambda_nm) const {
    const double disc_mass = surface::visible_disc_mass(*stats_, theta_i, lambda_nm);
    const double sigma = settings_.relevant_roughness ? stats_->sigma_h() * std::sqrt(disc_mass) : stats_->sigma_h();
    switch (settings_.normalization) {
        case LobeNormalization::none: return {sigma, 1.0};
        case LobeNormalization::disc_mass: return {sigma, 1.0 / disc_mass};
        case LobeNormalization::albedo: {
            const double a = 2.0 * wavenumber(lambda_nm) * sigma * std::cos(theta_i);
            const double mass = scatter_mass(theta_i, lambda_nm, sigma);
            return {sigma, mass > 0 ? -std::expm1(-a * a) / mass : 1.0};
        }
    }
    return {sigma, 1.0};
}

// Integral of the core density over the visible disc (d^2 zeta = k^2 d^2 q).
double GhsBsdf::scatter_mass(double theta_i, double lambda_nm, double sigma_um) const {
    const double k = wavenumber(lambda_nm);
    const double s = std::sin(theta_i), ci = std::cos(theta_i);
    // The lobe-following cubature of the albedo (the fixed rule before was 0.56 % off for KC(3 um, 0.3 um, gamma 1.2)
    // at 60 deg, so the albedo was 0.9944 where K should make it 1); the density from ln g and ln zeta as in eval (the
    // exact core's table is log-spaced): a third of the cost of density(g, zeta).
    return k * k * integrate_disc_adaptive(s, ci, [&](double q, double, double cos2_theta_o) {
               return core_->density_at_logs(2.0 * math::fast_log(k * sigma_um * (ci + std::sqrt(cos2_theta_o))),
                                             math::fast_log(k * q));
           }, 1e-6, jump_radius(lambda_nm)).value;
}

}  // namespace surfscatter::bsdf
