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

constexpr int kThetaNodes = 61;
constexpr double kThetaMax = 89.5 * kDegree;     // last node; grazing queries use it (the lobe vanishes there)
constexpr double kLambdaStep = 0.01;             // log-wavelength node spacing

constexpr std::array<double, 4> kGaussX{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                        0.8611363115940526};
constexpr std::array<double, 4> kGaussW{0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                        0.3478548451374538};
constexpr int kAzimuthNodes = 12;  // Gauss-Legendre nodes over the half wedge

struct GaussRule {
    std::array<double, kAzimuthNodes> x{}, w{};
    GaussRule() {
        // Golub-Welsch-free Newton iteration on Legendre roots.
        const int n = kAzimuthNodes;
        for (int i = 0; i < n; ++i) {
            double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), pp = 1;
            for (int it = 0; it < 100; ++it) {
                double p1 = 1, p2 = 0;
                for (int j = 1; j <= n; ++j) {
                    const double p3 = p2;
                    p2 = p1;
                    p1 = ((2.0 * j - 1) * z * p2 - (j - 1.0) * p3) / j;
                }
                pp = n * (z * p1 - p2) / (z * z - 1);
                const double dz = p1 / pp;
                z -= dz;
                if (std::abs(dz) < 1e-16) break;
            }
            x[i] = 0.5 * (1 - z);  // nodes on [0, 1]
            w[i] = 1.0 / ((1 - z * z) * pp * pp);  // weights on [0, 1] (2/((1-z^2)p'^2) * 1/2)
        }
    }
};
const GaussRule& azimuth_rule() {
    static const GaussRule rule;
    return rule;
}

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
    const double y = std::min(theta, kThetaMax) / kThetaMax * (kThetaNodes - 1);
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
        const double theta = kThetaMax * j / (kThetaNodes - 1);
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

// Integral of the core density over the visible disc, in polar coordinates about zeta = 0: radial composite
// Gauss-Legendre on panels spaced in log(zeta) and graded geometrically toward the two circles where the wedge
// half-angle has square-root kinks (q = 1 - s, q = 1 + s); azimuth phi = phi_max (1 - (1 - t)^2) to absorb the
// square-root behaviour of cos(theta_o) at the wedge edge. Accuracy ~1e-6 relative (tested by the furnace test).
double GhsBsdf::scatter_mass(double theta_i, double lambda_nm, double sigma_um) const {
    const double k = wavenumber(lambda_nm);
    const double s = std::sin(theta_i), ci = std::cos(theta_i);
    const double zeta_max = k * (1.0 + s), zeta_inner = k * (1.0 - s);
    const double length = stats_->correlation_length();
    const double zeta_lo = std::min(1e-5 / length, 1e-6 * zeta_max);
    std::vector<double> breaks;
    const double span = std::log(zeta_max / zeta_lo);
    const int log_panels = std::max(8, int(std::ceil(span / 0.15)));
    for (int i = 0; i <= log_panels; ++i) breaks.push_back(zeta_lo * std::exp(span * i / log_panels));
    if (s > 0) {
        const double width = zeta_max - zeta_inner;
        for (int j = 1; j <= 30; ++j) {
            const double d = width * std::ldexp(0.5, -j);
            breaks.push_back(zeta_max - d);
            breaks.push_back(zeta_inner + d);
            if (zeta_inner - d > zeta_lo) breaks.push_back(zeta_inner - d);
        }
        breaks.push_back(zeta_inner);
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    breaks.erase(std::remove_if(breaks.begin(), breaks.end(), [&](double z) { return z < zeta_lo || z > zeta_max; }),
                 breaks.end());
    const auto& rule = azimuth_rule();
    const Vec2 i_xy(s, 0.0);  // azimuth of i set to 0: the disc is symmetric about it
    auto ring = [&](double zeta) {
        const double q = zeta / k;
        const double phi_max = wedge_half_angle(q, s);
        if (!(phi_max > 0)) return 0.0;
        double sum = 0;
        for (int a = 0; a < kAzimuthNodes; ++a) {
            const double t = rule.x[a];
            const double phi = phi_max * (1.0 - (1.0 - t) * (1.0 - t));
            const double jac = 2.0 * phi_max * (1.0 - t);
            const double ox = q * std::cos(phi) - i_xy.x, oy = q * std::sin(phi);
            const double co = std::sqrt(std::max(0.0, 1.0 - ox * ox - oy * oy));
            const double g = k * sigma_um * (ci + co);
            sum += rule.w[a] * jac * core_->density(g * g, zeta);
        }
        return 2.0 * sum * zeta;  // both halves of the wedge, polar Jacobian
    };
    const double g_spec = 4.0 * k * k * sigma_um * sigma_um * ci * ci;
    double total = kPi * zeta_lo * zeta_lo * core_->density(g_spec, 0.0);
    for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
        const double a = breaks[p], b = breaks[p + 1];
        for (int q = 0; q < 4; ++q) {
            const double zeta = 0.5 * (a + b) + 0.5 * (b - a) * kGaussX[q];
            total += 0.5 * (b - a) * kGaussW[q] * ring(zeta);
        }
    }
    return total;
}

}  // namespace surfscatter::bsdf
