#include "surfscatter/bsdf/ghs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include <fmt/format.h>

#include "surfscatter/bsdf/node_axis.hpp"
#include "surfscatter/bsdf/rayleigh_rice.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/table_cache.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/simd_pair.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"

namespace surfscatter::bsdf {

namespace {

// Incidence nodes, in cos(theta_i): theta_j = 90 deg (1 - (1 - j / (kThetaNodes - 1))^3), dense toward grazing where
// sigma_rel and K vary fastest, the last one at cos theta_i = 1e-6 instead of 0 (NodeAxis needs positive nodes);
// wavelength nodes 2 % apart over [kMinWavelength, kMaxWavelength]. NodeAxis moves them to its cell edges (by at most
// 0.2 %).
constexpr double kMinCosine = 1e-6;
NodeAxis incidence_axis() {
    std::vector<double> cosines;
    for (int j = GhsBsdf::kThetaNodes - 1; j >= 0; --j) {
        const double u = double(j) / (GhsBsdf::kThetaNodes - 1);
        const double theta = 90.0 * kDegree * (1.0 - (1.0 - u) * (1.0 - u) * (1.0 - u));
        cosines.push_back(j == 0 ? 1.0 : std::max(kMinCosine, std::cos(theta)));
    }
    return NodeAxis(cosines);
}

// Cubic through (x[0], y[0]) .. (x[3], y[3]) as coefficients of d = x - a over [a, b] (a < b inside the nodes): from
// its values at t = (x - a) / (b - a) = 0, 1/3, 2/3, 1 (Lagrange), the monomial form in t, then c_n / (b - a)^n.
std::array<double, 4> interval_cubic(const double* x, const double* y, double a, double b) {
    std::array<double, 4> v{};
    for (int m = 0; m < 4; ++m) {
        const double at = a + (b - a) * m / 3.0;
        for (int i = 0; i < 4; ++i) {
            double w = y[i];
            for (int j = 0; j < 4; ++j)
                if (j != i) w *= (at - x[j]) / (x[i] - x[j]);
            v[m] += w;
        }
    }
    // p(t) = c0 + c1 t + c2 t^2 + c3 t^3 through v at t = 0, 1/3, 2/3, 1.
    const double h = b - a;
    return {v[0], (-11.0 * v[0] + 18.0 * v[1] - 9.0 * v[2] + 2.0 * v[3]) / (2.0 * h),
            (18.0 * v[0] - 45.0 * v[1] + 36.0 * v[2] - 9.0 * v[3]) / (2.0 * h * h),
            (-9.0 * v[0] + 27.0 * v[1] - 27.0 * v[2] + 9.0 * v[3]) / (2.0 * h * h * h)};
}
// Estrin's form in d: two independent multiply-adds, then one. Horner in t (three dependent ones after the multiply
// that makes t) made exact-GHS eval 5 % slower than the bilinear lookup before the cubic; this is as fast.
template <class Interval>
math::Pair estrin(const Interval& in, math::Pair d) {
    using math::load_pair;
    return (load_pair(in.c[0]) + load_pair(in.c[1]) * d) + (load_pair(in.c[2]) + load_pair(in.c[3]) * d) * (d * d);
}
NodeAxis wavelength_axis() {
    std::vector<double> lambdas{GhsBsdf::kMinWavelength};
    while (lambdas.back() < GhsBsdf::kMaxWavelength) lambdas.push_back(lambdas.back() * std::exp(0.02));
    return NodeAxis(lambdas);
}
[[noreturn, gnu::cold, gnu::noinline]] void wavelength_out_of_range(double lambda_nm) {
    fail("wavelength {} nm outside [{}, {}] nm", lambda_nm, GhsBsdf::kMinWavelength, GhsBsdf::kMaxWavelength);
}

const NodeAxis kIncidenceAxis = incidence_axis();
const NodeAxis kWavelengthAxis = wavelength_axis();

}  // namespace

GhsBsdf::GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
                 material::Conductor material, GhsSettings settings)
    : stats_(std::move(stats)), core_(std::move(core)), material_(std::move(material)),
      settings_(std::move(settings)), exact_(dynamic_cast<const ExactScatterCore*>(core_.get())),
      log_native_(exact_ && stats_->psd_jump_radius() == 0.0 ? &exact_->table() : nullptr),
      tables_(std::size_t(kWavelengthAxis.size())) {
    if (kIncidenceAxis.size() != kThetaNodes)
        fail("internal: {} incidence nodes, expected {}", kIncidenceAxis.size(), kThetaNodes);
}

[[gnu::always_inline]] inline GhsBsdf::Incidence GhsBsdf::lookup(double cos_theta_i, double lambda_nm,
                                                                  double k) const {
    if (!(lambda_nm >= kMinWavelength && lambda_nm <= kMaxWavelength)) wavelength_out_of_range(lambda_nm);
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

double GhsBsdf::specular_exponent(const Incidence& in, double cos_theta_i) {
    const double a = 2.0 * in.k * cos_theta_i;
    return a * a * math::fast_exp(2.0 * in.log_sigma);
}

inline double GhsBsdf::fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    return settings_.fresnel == FresnelMode::incident ? material_.reflectance(std::min(1.0, wi.z), lambda_nm)
                                                      : outgoing_fresnel(wi, wo, lambda_nm);
}

double GhsBsdf::outgoing_fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    switch (settings_.fresnel) {
        case FresnelMode::incident: break;
        case FresnelMode::half: {
            const Vec3 h = normalize(wi + wo);
            return material_.reflectance(std::clamp(dot(wi, h), 0.0, 1.0), lambda_nm);
        }
        case FresnelMode::rr: {
            if (material_.is_perfect()) return rayleigh_rice_q_perfect(wi, wo);
            const std::complex<double> n = material_.ior(lambda_nm);
            return rayleigh_rice_q(wi, wo, n * n);
        }
    }
    return 0.0;
}

double GhsBsdf::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    return eval(wi, wo, lambda_nm, lookup(wi.z, lambda_nm, k), LobeLogs(wi, wo, k));
}

// Inlined into its three callers: a call here, and to lookup, cost 20 % of an exact-GHS eval (register saves and
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
    BsdfSample out;
    if (u_lobe < p_delta) {
        out.wo = reflect_about_normal(wi);
        out.pdf = p_delta;
        out.weight = material_.reflectance(std::min(1.0, wi.z), lambda_nm);  // R e^{-g0} / e^{-g0}
        out.delta = true;
        return out;
    }
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
    constexpr std::uint32_t kVersion = 3;  // of build_table's construction and Interval's layout
    static_assert(std::is_trivially_copyable_v<Table> && sizeof(Table) % sizeof(double) == 0);
    const std::string key =
        fmt::format("ghs-incidence:{}:sigma_h={:.17g}:{}:normalization={}:relevant={}:lambda={:.17g}:nodes={}",
                    stats_->cache_key(), stats_->sigma_h(), core_->cache_key(), int(settings_.normalization),
                    settings_.relevant_roughness, lambda_nm, kThetaNodes);
    const auto file = table_cache_file("ghs-incidence", kVersion, key);
    Table t;
    if (const auto saved = load_cached_table(file, kVersion, key); saved && saved->size() * sizeof(double) == sizeof t) {
        std::memcpy(&t, saved->data(), sizeof t);
        return t;
    }
    t = build_table(lambda_nm);
    std::vector<double> payload(sizeof t / sizeof(double));
    std::memcpy(payload.data(), &t, sizeof t);
    save_cached_table(file, kVersion, key, payload);
    return t;
}

GhsBsdf::Table GhsBsdf::build_table(double lambda_nm) const {
    std::array<double, kThetaNodes> x{}, log_sigma{}, log_norm{};
    for (int j = 0; j < kThetaNodes; ++j) {
        x[j] = kIncidenceAxis.node(j);
        const Direct d = direct(std::acos(x[j]), lambda_nm);
        // Finite logarithms even for sigma = 0 or N = 0, for the interpolation.
        log_sigma[j] = std::log(std::max(d.sigma, std::numeric_limits<double>::min()));
        log_norm[j] = std::log(std::max(d.norm / norm_power(x[j]), std::numeric_limits<double>::min()));
    }
    Table t;
    for (int j = 0; j + 1 < kThetaNodes; ++j) {
        const int first = std::clamp(j - 1, 0, kThetaNodes - 4);  // the 4 nodes around the interval (one-sided at ends)
        const auto s = interval_cubic(&x[first], &log_sigma[first], x[j], x[j + 1]);
        const auto n = interval_cubic(&x[first], &log_norm[first], x[j], x[j + 1]);
        for (int p = 0; p < 4; ++p) t[j].c[p][0] = s[p], t[j].c[p][1] = n[p];
    }
    return t;
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
