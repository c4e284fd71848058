#pragma once
// What the GHS family's per-wavelength incidence tables share (GhsBsdf over cos theta_i; AnisotropicGhsBsdf over
// cos theta_i and the incidence azimuth relative to the lay): the node axes, the interval cubics in cos theta_i and
// their evaluation, the lobe's Fresnel factor and coherent delta, and the disk cache of a table.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/node_axis.hpp"
#include "surfscatter/core/table_cache.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/math/simd_pair.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf {

inline constexpr double kGhsMinWavelength = 0.1;  // nm
inline constexpr double kGhsMaxWavelength = 1e8;  // nm
inline constexpr int kGhsThetaNodes = 64;         // incidence nodes of the sigma / N tables

// Incidence nodes, in cos(theta_i): theta_j = 90 deg (1 - (1 - j / (kGhsThetaNodes - 1))^3), dense toward grazing
// where sigma_rel and K vary fastest, the last one at cos theta_i = 1e-6 instead of 0 (NodeAxis needs positive nodes);
// wavelength nodes 2 % apart over [kGhsMinWavelength, kGhsMaxWavelength]. NodeAxis moves them to its cell edges (by
// at most 0.2 %). Each table's .cpp keeps its own copy (read on every lookup, no static-local guard).
NodeAxis ghs_incidence_axis();
NodeAxis ghs_wavelength_axis();
[[noreturn, gnu::cold, gnu::noinline]] void ghs_wavelength_out_of_range(double lambda_nm);

// Cubic coefficients (in d = cos theta_i - the interval's first node) of two quantities (ln sigma and ln(N/cos^p))
// side by side, for one SSE2 pair per power of d.
struct CubicPairInterval {
    double c[4][2];
};
using IncidenceTable = std::array<CubicPairInterval, kGhsThetaNodes - 1>;  // over cos theta_i

// One incidence's values read from the tables: k in rad/um, ln sigma, ln(N / cos^p theta_i).
struct IncidenceLookup {
    double k, log_sigma, log_norm;
};

// The coherent part's exponent g0 = (2 k sigma cos theta_i)^2.
inline double specular_exponent(const IncidenceLookup& in, double cos_theta_i) {
    const double a = 2.0 * in.k * cos_theta_i;
    return a * a * math::fast_exp(2.0 * in.log_sigma);
}

// The table through (x_j, first_j, second_j) at the incidence nodes x_j: per interval the 4-point Lagrange cubic of
// the nodes around it (one-sided at the ends).
IncidenceTable fit_incidence_table(const std::array<double, kGhsThetaNodes>& x,
                                   const std::array<double, kGhsThetaNodes>& first,
                                   const std::array<double, kGhsThetaNodes>& second);

// The table of ln sigma and ln(N / norm_power(x)) at `axis`'s nodes x = cos theta_i, from direct_at(x) (a value with
// .sigma and .norm, e.g. GhsBsdf::Direct); each logarithm finite even for sigma = 0 or N = 0, for the interpolation.
template <class DirectAt, class NormPower>
IncidenceTable tabulate_incidence(const NodeAxis& axis, DirectAt&& direct_at, NormPower&& norm_power) {
    std::array<double, kGhsThetaNodes> x{}, log_sigma{}, log_norm{};
    for (int j = 0; j < kGhsThetaNodes; ++j) {
        x[j] = axis.node(j);
        const auto d = direct_at(x[j]);
        log_sigma[j] = std::log(std::max(d.sigma, std::numeric_limits<double>::min()));
        log_norm[j] = std::log(std::max(d.norm / norm_power(x[j]), std::numeric_limits<double>::min()));
    }
    return fit_incidence_table(x, log_sigma, log_norm);
}

// Estrin's form in d: two independent multiply-adds, then one. Horner in t (three dependent ones after the multiply
// that makes t) made exact-GHS eval 5 % slower than the bilinear lookup before the cubic; this is as fast.
inline math::Pair estrin(const CubicPairInterval& in, math::Pair d) {
    using math::load_pair;
    return (load_pair(in.c[0]) + load_pair(in.c[1]) * d) + (load_pair(in.c[2]) + load_pair(in.c[3]) * d) * (d * d);
}

// The lobe's Fresnel factor F(i, o) for --fresnel (THEORY 1.3): R(theta_i), or the half-vector and Rayleigh-Rice
// forms (outgoing_fresnel, out of line).
double outgoing_fresnel(const material::Conductor& material, FresnelMode mode, const Vec3& wi, const Vec3& wo,
                        double lambda_nm);
inline double lobe_fresnel(const material::Conductor& material, FresnelMode mode, const Vec3& wi, const Vec3& wo,
                           double lambda_nm) {
    return mode == FresnelMode::incident ? material.reflectance(std::min(1.0, wi.z), lambda_nm)
                                         : outgoing_fresnel(material, mode, wi, wo, lambda_nm);
}

// The coherent delta, drawn with probability p_delta = e^{-g0}: the mirror direction, weight R e^{-g0} / e^{-g0}.
inline BsdfSample coherent_delta_sample(const material::Conductor& material, const Vec3& wi, double lambda_nm,
                                        double p_delta) {
    BsdfSample out;
    out.wo = reflect_about_normal(wi);
    out.pdf = p_delta;
    out.weight = material.reflectance(std::min(1.0, wi.z), lambda_nm);
    out.delta = true;
    return out;
}

// A trivially copyable table from the disk cache under `key` (naming everything it depends on), else build() and
// saved there.
template <class Table, class Build>
Table cached_incidence_table(const std::string& kind, std::uint32_t version, const std::string& key, Build&& build) {
    static_assert(std::is_trivially_copyable_v<Table> && sizeof(Table) % sizeof(double) == 0);
    const auto file = table_cache_file(kind, version, key);
    Table t;
    if (const auto saved = load_cached_table(file, version, key); saved && saved->size() * sizeof(double) == sizeof t) {
        std::memcpy(&t, saved->data(), sizeof t);
        return t;
    }
    t = build();
    std::vector<double> payload(sizeof t / sizeof(double));
    std::memcpy(payload.data(), &t, sizeof t);
    save_cached_table(file, version, key, payload);
    return t;
}

}  // namespace surfscatter::bsdf
