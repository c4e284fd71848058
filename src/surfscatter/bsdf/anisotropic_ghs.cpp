#include "surfscatter/bsdf/anisotropic_ghs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/lagrange.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::bsdf {

namespace {

const NodeAxis kIncidenceAxis = ghs_incidence_axis();
const NodeAxis kWavelengthAxis = ghs_wavelength_axis();
constexpr int kLastAzimuth = AnisotropicGhsBsdf::kAzimuthNodes - 1;

// The azimuth nodes are uniform in x = kLastAzimuth (2 phi_r / pi + kAzimuthGrading sin(4 phi_r) / (2 pi)), phi_r in
// [0, 90] deg: 1 + kAzimuthGrading times denser than uniform at the lay and at its normal (where grazing incidence
// makes the tables change fastest: along the longer correlation length, which is the lay's normal when LV > LU),
// 1 - kAzimuthGrading at 45 deg. x is odd about phi_r = 0, x(90 + d) = 2 x(90) - x(90 - d), and x(90 - phi) =
// kLastAzimuth - x(phi): the tables, even about 0 and 90 deg, stay smooth in x across both ends (the stencil is
// reflected there), and relabelling the surface (A + 90 deg, LU and LV swapped) reads mirrored nodes.
constexpr double kAzimuthGrading = 0.3;

// x of incidence with lay components uv (0 at normal incidence, where every azimuth node holds the same values).
double azimuth_coordinate(Vec2 uv) {
    const double u = std::abs(uv.x), v = std::abs(uv.y), r2 = u * u + v * v;
    const double sin_4phi = r2 > 0 ? 4.0 * u * v * (u * u - v * v) / (r2 * r2) : 0.0;
    return kLastAzimuth * (std::atan2(v, u) + 0.25 * kAzimuthGrading * sin_4phi) / (0.5 * kPi);
}

// phi_r of azimuth node a (x = a), by bisection (x increases with phi_r).
double azimuth_node_angle(int a) {
    double lo = 0.0, hi = 0.5 * kPi;
    for (int step = 0; step < 60; ++step) {
        const double mid = 0.5 * (lo + hi);
        (azimuth_coordinate({std::cos(mid), std::sin(mid)}) < a ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// Node j of the 4-point stencil, reflected at phi_r = 0 and 90 deg (the tables are even about both).
int reflected_azimuth(int j) { return j < 0 ? -j : (j > kLastAzimuth ? 2 * kLastAzimuth - j : j); }

}  // namespace

AnisotropicGhsBsdf::AnisotropicGhsBsdf(std::shared_ptr<const surface::EllipticalStatistics> stats,
                                       std::shared_ptr<const ScatterCore> core, material::Conductor material,
                                       GhsSettings settings)
    : stats_(std::move(stats)), core_(std::move(core)), material_(std::move(material)),
      settings_(std::move(settings)), tables_(std::size_t(kWavelengthAxis.size())) {
    if (!stats_ || !core_) fail("anisotropic {} needs elliptical statistics and a scatter core", settings_.name);
    stretch_ = stats_->stretch();
    stretch2_ = stretch_ * stretch_;
    // A PSD with a jump (the two-scale micro part) has no log-valued table: the core adds its first order exactly.
    const auto* exact = dynamic_cast<const ExactScatterCore*>(core_.get());
    log_native_ = exact && stats_->radial().psd_jump_radius() == 0.0 ? &exact->table() : nullptr;
}

[[gnu::always_inline]] inline AnisotropicGhsBsdf::Incidence AnisotropicGhsBsdf::lookup(const Vec3& wi,
                                                                                        double lambda_nm,
                                                                                        double k) const {
    if (!(lambda_nm >= kGhsMinWavelength && lambda_nm <= kGhsMaxWavelength)) ghs_wavelength_out_of_range(lambda_nm);
    const NodeAxis::Position l = kWavelengthAxis.position(lambda_nm);
    const double cosine = std::clamp(wi.z, kIncidenceAxis.node(0), 1.0);
    const int c = kIncidenceAxis.position(cosine).interval;
    const math::Pair d = math::Pair{1.0, 1.0} * (cosine - kIncidenceAxis.node(c));
    // Azimuth: the 4 nodes around x (uniform in x, reflected at the ends), Lagrange weights at t.
    double x = azimuth_coordinate(stats_->to_lay({wi.x, wi.y}));
    if (!(x >= 0.0)) x = 0.0;
    x = std::min(x, double(kLastAzimuth));
    const int first = std::clamp(int(x) - 1, -1, kLastAzimuth - 2);
    const double t = x - first;
    const std::array<double, 4> w = math::lagrange4_weights(t);
    auto table = [&](int slot) -> const AzimuthTables& {
        return tables_.get(std::size_t(slot), [&] { return cached_tables(kWavelengthAxis.node(slot)); });
    };
    auto at = [&](const AzimuthTables& tables) {
        math::Pair v{0.0, 0.0};
        for (int j = 0; j < 4; ++j)
            v += w[j] * estrin(tables[std::size_t(reflected_azimuth(first + j))][std::size_t(c)], d);
        return v;
    };
    const math::Pair at_a = at(table(l.interval)), v = at_a + l.t * (at(table(l.interval + 1)) - at_a);
    return {k, v[0], v[1]};
}

AnisotropicGhsBsdf::Incidence AnisotropicGhsBsdf::lookup(const Vec3& wi, double lambda_nm) const {
    return lookup(wi, lambda_nm, wavenumber(lambda_nm));
}

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
    return std::exp(-specular_exponent(in, wi.z));
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
    const double k = in.k, g0 = specular_exponent(in, wi.z);
    const double w = k * stretched(wi.x + wo.x, wi.y + wo.y);
    const double p = math::one_minus_exp(g0) * stretch_ * k * k * wo.z *
                     core_->sample_density(g0, stretched_zeta_max(wi, k), w);
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> AnisotropicGhsBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const Incidence in = lookup(wi, lambda_nm);
    const double k = in.k, g0 = specular_exponent(in, wi.z);
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
    // The tables are over phi_i - A (build_tables, lookup): a new lay angle is a rotation of the local frame that
    // they already hold, so the key leaves A out (shape_key) and every lay angle of a surface shares them.
    constexpr std::uint32_t kVersion = 5;  // of build_tables' construction and the layout
    const std::string key = fmt::format(
        "ghs-anisotropic-incidence:{}:sigma_h={:.17g}:{}:normalization={}:relevant={}:lambda={:.17g}:nodes={}x{}"
        ":azimuth=2(phi-A)/pi+{}sin(4(phi-A))/2pi",
        stats_->shape_key(), stats_->sigma_h(), core_->cache_key(), int(settings_.normalization),
        settings_.relevant_roughness, lambda_nm, kGhsThetaNodes, kAzimuthNodes, kAzimuthGrading);
    return cached_incidence_table<AzimuthTables>("ghs-anisotropic-incidence", kVersion, key,
                                                 [&] { return build_tables(lambda_nm); });
}

AnisotropicGhsBsdf::AzimuthTables AnisotropicGhsBsdf::build_tables(double lambda_nm) const {
    AzimuthTables tables;
    for (int a = 0; a < kAzimuthNodes; ++a) {
        const double phi_r = azimuth_node_angle(a);
        const Vec2 along = stats_->from_lay({std::cos(phi_r), std::sin(phi_r)});
        tables[std::size_t(a)] = tabulate_incidence(
            kIncidenceAxis,
            [&](double cos_theta_i) {
                const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta_i * cos_theta_i));
                return direct(Vec3(s * along.x, s * along.y, cos_theta_i), lambda_nm);
            },
            [this](double c) { return norm_power(c); });
    }
    return tables;
}

// The visible disc in the stretched plane w = (q_u, s q_v) (q = i_xy + o_xy in lay components): an ellipse about
// the specular point w = 0, the lobe a function of |w| (and of g, through cos theta_o). Along the ray of angle psi,
// w = rho (cos psi, sin psi), q = t e with e = a (cos psi, sin psi / s) a unit vector, rho = a t; the ray leaves the disc
// at t = q_max = b + sqrt(b^2 + cos^2 theta_i), b = sin theta_i (e . i_uv), and there cos^2 theta_o =
// (q_max - t)(t + cos^2 theta_i / q_max) (the factored form has no cancellation near the horizon).
AnisotropicGhsBsdf::DiscRays::DiscRays(const AnisotropicGhsBsdf& bsdf, const Vec3& wi)
    : stretch(bsdf.stretch_), sin_i(sin_theta(wi)), cos2_i(wi.z * wi.z),
      incidence(sin_i > 0 ? bsdf.stats_->to_lay({wi.x / sin_i, wi.y / sin_i}) : Vec2{1.0, 0.0}) {
    // The quarters between e = i_uv, its normal, -i_uv and minus its normal (b = 0 where the horizon comes closest at
    // grazing incidence): their images in psi, increasing (the map keeps orientation).
    auto angle = [&](Vec2 e) { return std::atan2(stretch * e.y, e.x); };
    const double first = angle(incidence);
    double second = angle({-incidence.y, incidence.x});
    while (second <= first) second += kTwoPi;
    edges = {first, second, first + kPi, second + kPi, first + kTwoPi};
}

AnisotropicGhsBsdf::DiscRays::Ray AnisotropicGhsBsdf::DiscRays::at(double psi) const {
    const double ex = std::cos(psi), ey = std::sin(psi) / stretch, a = 1.0 / std::sqrt(ex * ex + ey * ey);
    const double b = sin_i * a * (ex * incidence.x + ey * incidence.y), root = std::sqrt(b * b + cos2_i);
    const double q_max = b >= 0 ? b + root : cos2_i / (root - b);  // no cancellation for b < 0
    return {a, q_max, a * q_max};
}

// Integral over psi of f(ray) by adaptive Gauss-Kronrod on each quarter, to rel_tol of the whole (abs_scale: its size).
// Near grazing incidence the specular point lies cos^2 theta_i / 2 from the horizon and q_max falls from ~2 to ~0
// across the ray at b = 0, over |b| ~ cos theta_i: each quarter is integrated in v, psi = psi_0 +- c sinh v from its
// b = 0 end psi_0, with c that width in psi (b = cos theta_i sinh v there: q_max = cos theta_i e^{+-v}, smooth in v).
double AnisotropicGhsBsdf::DiscRays::integrate(const std::function<double(const Ray&)>& f, double rel_tol,
                                                double abs_scale) const {
    constexpr double kGradedFraction = 0.1;  // of the quarter: a transition narrower than this is graded
    double total = 0;
    for (int quarter = 0; quarter < 4; ++quarter) {
        const bool upper = quarter % 2 == 0;  // b = 0 at the quarter's upper end (quarters 0 and 2)
        const double lo = edges[std::size_t(quarter)], hi = edges[std::size_t(quarter) + 1];
        const double end = upper ? hi : lo, width = hi - lo, sign = upper ? -1.0 : 1.0;
        // dpsi / dphi = s / a^2 on the b = 0 ray (phi: the ray's angle in the q plane), where |e . i_uv| = 0.
        const Ray edge = at(end);
        const double scale = sin_i > 0 ? std::sqrt(cos2_i) / sin_i * stretch / (edge.a * edge.a) : width;
        if (scale > kGradedFraction * width) {  // no narrow transition: the plain angle is the better variable
            total += math::integrate_adaptive([&](double psi) { return f(at(psi)); }, lo, hi, rel_tol,
                                              0.25 * rel_tol * abs_scale);
            continue;
        }
        total += math::integrate_adaptive([&](double v) {
            return scale * std::cosh(v) * f(at(end + sign * scale * std::sinh(v)));
        }, 0.0, std::asinh(width / scale), rel_tol, 0.25 * rel_tol * abs_scale);
    }
    return total;
}

// P-hat(zeta) d^2 zeta = P_radial(k |w|) k^2 d^2 w: a ray carries F(k rho_max) / (2 pi) dpsi, F the radial CDF (closed
// form for KC and Gaussian).
double AnisotropicGhsBsdf::visible_disc_mass(const Vec3& wi, double k) const {
    const DiscRays rays(*this, wi);
    const double mass = rays.integrate([&](const DiscRays::Ray& r) {
        return stats_->radial().radial_cdf(k * r.rho_max) / kTwoPi;
    }, 1e-7, 1.0);
    return std::clamp(mass, 0.0, 1.0);
}

// k^2 s integral over the disc of S_g,radial(k |w|) d^2 q = k^2 integral of S_g(k rho) rho drho dpsi (d^2 w = s d^2 q).
// Along each ray a fixed Gauss-Legendre rule: rho = rho_max e^u over u in [ln 1e-6, ln 1/2] (the lobe down to 1e-6 of
// the ray: rho^2 S in u is a bump a few units wide; the disc left out holds ~(1e-6 rho_max / lobe width)^2 of it), then
// rho = rho_max (1 - tau^2 / 2) over tau in [0, 1] (cos theta_o ~ tau there: smooth in tau); over psi adaptive to 1e-4
// (the error estimate; the result is ~1e-5 off, AnisotropicGhs.TablesMatchDirectQuadrature).
double AnisotropicGhsBsdf::scatter_mass(const Vec3& wi, double k, double sigma) const {
    // The rule in rho / rho_max, the same on every ray: nodes, 1 - node (exact near the horizon), their logarithms and
    // weights (with the Jacobians).
    struct RayRule {
        std::array<double, kLobeNodes + kHorizonNodes> fraction, complement, log_fraction, weight;
        RayRule() {
            const math::GaussLegendreRule lobe(kLobeNodes), horizon(kHorizonNodes);
            constexpr double kLogInner = -13.815510557964274, kLogOuter = -0.69314718055994531;  // ln 1e-6, ln 0.5
            const double half_u = 0.5 * (kLogOuter - kLogInner), mid_u = 0.5 * (kLogOuter + kLogInner);
            for (std::size_t j = 0; j < std::size_t(kLobeNodes); ++j) {  // d rho = rho du: rho^2 du
                log_fraction[j] = mid_u + half_u * lobe.nodes[j];
                fraction[j] = std::exp(log_fraction[j]);
                complement[j] = -std::expm1(log_fraction[j]);
                weight[j] = half_u * lobe.weights[j] * fraction[j] * fraction[j];
            }
            for (std::size_t j = 0; j < std::size_t(kHorizonNodes); ++j) {  // d rho = rho_max tau d tau: rho tau d tau
                const double tau = 0.5 * (1.0 + horizon.nodes[j]);
                const std::size_t i = std::size_t(kLobeNodes) + j;
                complement[i] = 0.5 * tau * tau;
                fraction[i] = 1.0 - complement[i];
                log_fraction[i] = std::log(fraction[i]);
                weight[i] = 0.5 * horizon.weights[j] * fraction[i] * tau;
            }
        }
    };
    static const RayRule kRule;
    const DiscRays rays(*this, wi);
    const double ci = wi.z, log_k_sigma = std::log(k * sigma), log_k = std::log(k);
    auto along = [&](const DiscRays::Ray& r) {
        const double far = rays.cos2_i / r.q_max, log_rho_max = log_k + std::log(r.rho_max);
        double sum = 0;
        for (std::size_t j = 0; j < kRule.fraction.size(); ++j) {
            const double t = r.q_max * kRule.fraction[j];
            const double cos_theta_o = std::sqrt(r.q_max * kRule.complement[j] * (t + far));  // (q_max - t)(t + far)
            const double log_g = 2.0 * (log_k_sigma + math::fast_log(ci + cos_theta_o));
            const double log_zeta = log_rho_max + kRule.log_fraction[j];
            sum += kRule.weight[j] * (log_native_ ? math::fast_exp(log_native_->log_eval_at_logs(log_g, log_zeta))
                                                  : core_->density_at_logs(log_g, log_zeta));
        }
        return sum * r.rho_max * r.rho_max;
    };
    // A PSD that jumps (the two-scale micro part) jumps on the circle |w| = rho_jump of the stretched plane: rays that
    // cross it take the rule on each side, rho = lo + (hi - lo) f (the rule's weight / fraction is its df weight).
    const double rho_jump = stats_->radial().psd_jump_radius() / k;
    auto piece = [&](const DiscRays::Ray& r, double lo, double hi) {
        const double far = rays.cos2_i / r.q_max, width = hi - lo;
        double sum = 0;
        for (std::size_t j = 0; j < kRule.fraction.size(); ++j) {
            const double rho = lo + width * kRule.fraction[j], t = rho / r.a;
            const double gap = hi == r.rho_max ? width * kRule.complement[j] / r.a : r.q_max - t;  // q_max - t
            const double cos_theta_o = std::sqrt(gap * (t + far));
            sum += kRule.weight[j] / kRule.fraction[j] * rho *
                   core_->density_at_logs(2.0 * (log_k_sigma + math::fast_log(ci + cos_theta_o)), log_k + std::log(rho));
        }
        return sum * width;
    };
    auto split = [&](const DiscRays::Ray& r) {
        return rho_jump < r.rho_max ? piece(r, 0.0, rho_jump) + piece(r, rho_jump, r.rho_max) : along(r);
    };
    const double g0 = (2.0 * k * sigma * ci) * (2.0 * k * sigma * ci);
    if (rho_jump > 0) return k * k * rays.integrate(split, 1e-4, -std::expm1(-g0) / (k * k));
    return k * k * rays.integrate(along, 1e-4, -std::expm1(-g0) / (k * k));
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
            const double mass = scatter_mass(wi, k, sigma);
            return {sigma, mass > 0 ? -std::expm1(-a * a) / mass : 1.0};
        }
    }
    return {sigma, 1.0};
}

}  // namespace surfscatter::bsdf
