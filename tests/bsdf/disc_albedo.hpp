#pragma once
// Directional albedo by a quadrature written for the tests (not the library's integrate_disc_adaptive, which K itself
// uses): int f cos dw = int f d^2 o_xy over the disc of projected directions, in polar coordinates (q, phi) about the
// specular point, q = |i_xy + o_xy|. q: 8-node Gauss-Legendre panels, geometric (ratio 1.25) from q = 1e-12, with edges
// at the given radii (a lobe's jumps, e.g. zeta_c / k) and at 1 - s, graded geometrically (24 levels) toward the
// square-root kinks of the arc at 1 - s and 1 + s; phi: the arc [-phi_max, phi_max] (symmetric for isotropic BSDFs),
// phi = phi_max sin(pi t / 2) with 10-node Gauss-Legendre in t, which absorbs the square root of cos(theta_o) at the
// arc's ends; arcs whose end comes near the horizon (cos^2 theta_o < 0.1 there), where a rough lobe can grow by orders
// of magnitude within a layer as thin as cos^2 theta_i, instead as [0, phi_max/2] (10 nodes) and 40 panels halving
// toward phi_max (4 nodes each). The disc q < 1e-12 counts as pi q^2 f(specular). Plus the delta reflectance. Checked on lobes with known
// albedo (Lambert, Gaussian spikes 1e-5 to 0.3 wide about the specular direction) in test_models.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/model_options.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::bsdf::test {

inline double disc_albedo(const Bsdf& bsdf, const Vec3& wi, double lambda_nm, const std::vector<double>& jumps = {}) {
    static const auto rule = [] {
        std::vector<double> x8, w8, x10, w10, x4, w4;
        math::gauss_legendre(8, x8, w8);
        math::gauss_legendre(10, x10, w10);
        math::gauss_legendre(4, x4, w4);
        return std::array<std::vector<double>, 6>{x8, w8, x10, w10, x4, w4};
    }();
    const double s = std::sqrt(std::max(0.0, 1.0 - wi.z * wi.z)), phi_i = s > 0 ? std::atan2(wi.y, wi.x) : 0.0;
    const double q_end = 1.0 + s, q_inner = 1.0 - s, q_lo = 1e-12;
    std::vector<double> edges{q_lo, q_end};
    for (double q = q_lo; q < q_end; q *= 1.25) edges.push_back(q);
    for (double q : jumps) edges.push_back(q);
    if (s > 0) edges.push_back(q_inner);
    for (int j = 1; j <= 24; ++j) {
        const double d = std::ldexp(1.0, -j);
        edges.push_back(q_end - d * std::max(2.0 * s, 0.5));
        if (s > 0) {
            edges.push_back(q_inner + d * 2.0 * s);
            edges.push_back(q_inner - d * 0.5);
        }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::remove_if(edges.begin(), edges.end(), [&](double q) { return q < q_lo || q > q_end; }), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    auto brdf = [&](double q, double phi) {
        const double ox = q * std::cos(phi_i + phi) - wi.x, oy = q * std::sin(phi_i + phi) - wi.y;
        const double z2 = 1.0 - ox * ox - oy * oy;
        return z2 > 0 ? bsdf.eval(wi, Vec3(ox, oy, std::sqrt(z2)), lambda_nm) : 0.0;
    };
    double total = kPi * q_lo * q_lo * brdf(0.5 * q_lo, 0.0);
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
        const double a = edges[e], b = edges[e + 1];
        for (std::size_t i = 0; i < rule[0].size(); ++i) {
            const double q = 0.5 * (a + b) + 0.5 * (b - a) * rule[0][i];
            const double pm = q <= q_inner ? kPi : std::acos(std::clamp((q * q + s * s - 1.0) / (2.0 * q * s), -1.0, 1.0));
            const double reach = q < q_inner ? 1.0 - (q + s) * (q + s) : 0.0;  // cos^2 theta_o at the arc's end
            double arc = 0;
            if (reach < 0.1) {
                for (std::size_t k = 0; k < rule[2].size(); ++k)
                    arc += 0.25 * rule[3][k] * pm * brdf(q, 0.25 * pm * (1.0 + rule[2][k]));
                for (int j = 1; j <= 40; ++j) {
                    const double lo = std::ldexp(pm, -j - 1), hi = std::ldexp(pm, -j);  // distance to the arc's end
                    for (std::size_t k = 0; k < rule[4].size(); ++k)
                        arc += 0.5 * (hi - lo) * rule[5][k] * brdf(q, pm - (0.5 * (lo + hi) + 0.5 * (hi - lo) * rule[4][k]));
                }
            } else {
                for (std::size_t k = 0; k < rule[2].size(); ++k) {
                    const double t = 0.5 * (1.0 + rule[2][k]);
                    arc += 0.5 * rule[3][k] * pm * 0.5 * kPi * std::cos(0.5 * kPi * t) * brdf(q, pm * std::sin(0.5 * kPi * t));
                }
            }
            total += 0.5 * (b - a) * rule[1][i] * 2.0 * arc * q;
        }
    }
    return total + bsdf.delta_reflectance(wi, lambda_nm);
}

// The radii (in q = |zeta|/k) where a model's lobe jumps at wavelength lambda: the two-scale micro lobe's hole.
inline std::vector<double> lobe_jumps(const ModelOptions& o, double lambda_nm) {
    if (o.model != ModelKind::two_scale) return {};
    return {surface::cutoff_frequency(kTwoScaleReferenceWavelength, o.cutoff_wavelengths) / wavenumber(lambda_nm)};
}

}  // namespace surfscatter::bsdf::test
