#include "surfscatter/bsdf/ghs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <mutex>

#include "surfscatter/bsdf/rayleigh_rice.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr int kThetaNodes = 46;
constexpr double kThetaMax = 89.5 * kDegree;  // last node; grazing queries use it (the lobe vanishes there)
constexpr double kLambdaStep = 0.02;          // log-wavelength node spacing (2 %)

}  // namespace

GhsBsdf::GhsBsdf(std::shared_ptr<const surface::RadialStatistics> stats, std::shared_ptr<const ScatterCore> core,
                 material::Conductor material, GhsSettings settings)
    : stats_(std::move(stats)), core_(std::move(core)), material_(std::move(material)),
      settings_(std::move(settings)) {}

double GhsBsdf::core_lobe(const Vec3& wi, const Vec3& wo, double lambda_nm, double sigma_um) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    const double a = k * sigma_um * (wi.z + wo.z);
    return k * k * core_->density(a * a, k * scatter_radius(wi, wo));
}

double GhsBsdf::fresnel(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    switch (settings_.fresnel) {
        case FresnelMode::incident: return material_.reflectance(std::min(1.0, wi.z), lambda_nm);
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
    const Node n = lookup(wi.z, lambda_nm);
    const double f = fresnel(wi, wo, lambda_nm) * n.norm * core_lobe(wi, wo, lambda_nm, n.sigma);
    return std::isfinite(f) ? f : 0.0;
}

double GhsBsdf::delta_probability(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    const double a = 2.0 * wavenumber(lambda_nm) * lookup(wi.z, lambda_nm).sigma * wi.z;
    return std::exp(-a * a);
}

double GhsBsdf::delta_reflectance(const Vec3& wi, double lambda_nm) const {
    if (wi.z <= 0) return 0.0;
    return material_.reflectance(std::min(1.0, wi.z), lambda_nm) * delta_probability(wi, lambda_nm);
}

double GhsBsdf::pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0;
    const double k = wavenumber(lambda_nm);
    const double sigma = lookup(wi.z, lambda_nm).sigma;
    const double a = 2.0 * k * sigma * wi.z, g0 = a * a;
    const double s = sin_theta(wi);
    const double q = scatter_radius(wi, wo);
    const double zeta_max = k * (1.0 + s);
    const double p = -std::expm1(-g0) *
                     wedge_pdf(k, wo.z, core_->sample_density(g0, zeta_max, k * q), wedge_half_angle(q, s));
    return std::isfinite(p) ? p : 0.0;
}

std::optional<BsdfSample> GhsBsdf::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    if (wi.z <= 0) return std::nullopt;
    const double k = wavenumber(lambda_nm);
    const double sigma = lookup(wi.z, lambda_nm).sigma;
    const double a = 2.0 * k * sigma * wi.z, g0 = a * a;
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
    out.pdf = pdf(wi, *wo, lambda_nm);
    if (!(out.pdf > 0) || !std::isfinite(out.pdf)) return std::nullopt;
    out.weight = eval(wi, *wo, lambda_nm) * wo->z / out.pdf;
    if (!std::isfinite(out.weight)) return std::nullopt;
    return out;
}

GhsBsdf::Node GhsBsdf::lookup(double cos_theta_i, double lambda_nm) const {
    const double x = std::log(lambda_nm) / kLambdaStep;
    const int l0 = int(std::floor(x));
    const double tl = x - l0;
    const double theta = std::acos(std::clamp(cos_theta_i, 0.0, 1.0));
    // Nodes uniform in u = 1 - sqrt(1 - theta/theta_max): dense toward grazing, where sigma_rel and K vary fastest.
    const double y = (1.0 - std::sqrt(1.0 - std::min(theta, kThetaMax) / kThetaMax)) * (kThetaNodes - 1);
    const int t0 = std::min(kThetaNodes - 2, int(y));
    const double tt = y - t0;
    const Table& a = table(l0);
    const Table& b = table(l0 + 1);
    auto at = [&](const Table& t) {
        const Node& n0 = t.nodes[t0];
        const Node& n1 = t.nodes[t0 + 1];
        return Node{n0.sigma + tt * (n1.sigma - n0.sigma), n0.norm + tt * (n1.norm - n0.norm)};
    };
    const Node na = at(a), nb = at(b);
    return {na.sigma + tl * (nb.sigma - na.sigma), na.norm + tl * (nb.norm - na.norm)};
}

const GhsBsdf::Table& GhsBsdf::table(int lambda_node) const {
    {
        std::shared_lock lock(mutex_);
        const auto it = tables_.find(lambda_node);
        if (it != tables_.end()) return *it->second;
    }
    auto built = std::make_unique<Table>(build_table(std::exp(lambda_node * kLambdaStep)));
    std::unique_lock lock(mutex_);
    auto [it, inserted] = tables_.emplace(lambda_node, std::move(built));
    return *it->second;
}

GhsBsdf::Table GhsBsdf::build_table(double lambda_nm) const {
    Table t;
    t.nodes.resize(kThetaNodes);
    const double sigma_h = stats_->sigma_h();
    for (int j = 0; j < kThetaNodes; ++j) {
        const double u = double(j) / (kThetaNodes - 1);
        const double theta = kThetaMax * (1.0 - (1.0 - u) * (1.0 - u));
        Node& n = t.nodes[j];
        const double disc_mass = surface::visible_disc_mass(*stats_, theta, lambda_nm);
        n.sigma = settings_.relevant_roughness ? sigma_h * std::sqrt(disc_mass) : sigma_h;
        switch (settings_.normalization) {
            case LobeNormalization::none: n.norm = 1.0; break;
            case LobeNormalization::disc_mass: n.norm = 1.0 / disc_mass; break;
            case LobeNormalization::albedo: {
                const double a = 2.0 * wavenumber(lambda_nm) * n.sigma * std::cos(theta);
                const double mass = scatter_mass(theta, lambda_nm, n.sigma);
                n.norm = mass > 0 ? -std::expm1(-a * a) / mass : 1.0;
                break;
            }
        }
    }
    return t;
}

// Integral of the core density over the visible disc (d^2 zeta = k^2 d^2 q).
double GhsBsdf::scatter_mass(double theta_i, double lambda_nm, double sigma_um) const {
    const double k = wavenumber(lambda_nm);
    const double s = std::sin(theta_i), ci = std::cos(theta_i);
    const double q_lo = 1e-5 / (k * stats_->correlation_length());
    return k * k * integrate_visible_disc(s, q_lo, [&](double q, double phi) {
               const double ox = q * std::cos(phi) - s, oy = q * std::sin(phi);
               const double co = std::sqrt(std::max(0.0, 1.0 - ox * ox - oy * oy));
               const double a = k * sigma_um * (ci + co);
               return core_->density(a * a, k * q);
           });
}

}  // namespace surfscatter::bsdf
