#pragma once
// Reference directional albedos written for the tests, independent of the library's integrators (bsdf/albedo.cpp's
// lobe-following cubature over (ln q, w) about the specular point, and math/quadrature.hpp):
//  * hemisphere_albedo: nested globally adaptive Gauss-Kronrod (7-15; relative tolerance 1e-7 outside, 1e-9 inside,
//    at most 500 and 300 intervals) in the hemisphere's own angles, int_0^{pi/2} sin cos dtheta_o 2 int_0^pi f dpsi
//    (psi the azimuth from the specular plane), pre-cut geometrically (ratio 8, down to 1e-12) toward theta_i and the horizon in theta_o and toward the
//    specular plane in psi, so that no lobe wider than 1e-12 rad falls between the rule's nodes; plus the delta.
//  * ggx_slope_albedo: GGX with height-correlated Smith masking for a perfect conductor, integrated over the slopes
//    of the microfacets scaled by alpha (where the lobe is alpha-independent): albedo = int P22(p) (cos i - i.p-slope)
//    / cos i * G2(i, o(m)) d^2 p, in polar coordinates r = tan(beta): the probability-weighted visible normals, no BRDF
//    evaluation at all.
#include <cmath>
#include <functional>
#include <queue>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"

namespace surfscatter::bsdf::test {

// Sum over the intervals between `edges` of int f, globally adaptive 7-15 Gauss-Kronrod: the interval with the largest
// |Kronrod - Gauss| is bisected until their sum is <= rel_tol |estimate| or there are max_intervals intervals. (A
// recursive rule with a tolerance halved per level never stops when f is itself an inner integral with rounding-level
// noise.)
inline double nested_kronrod(const std::function<double(double)>& f, const std::vector<double>& edges, double rel_tol,
                             std::size_t max_intervals = 3000) {
    static constexpr double xk[8] = {0.991455371120812639, 0.949107912342758525, 0.864864423359769073,
                                     0.741531185599394440, 0.586087235467691130, 0.405845151377397167,
                                     0.207784955007898468, 0.0};
    static constexpr double wk[8] = {0.022935322010529225, 0.063092092629978553, 0.104790010322250184,
                                     0.140653259715525919, 0.169004726639267903, 0.190350578064785410,
                                     0.204432940075298892, 0.209482141084727828};
    static constexpr double wg[4] = {0.129484966168869693, 0.279705391489276668, 0.381830050505118945,
                                     0.417959183673469388};
    struct Interval {
        double a, b, value, error;
        bool operator<(const Interval& o) const { return error < o.error; }
    };
    auto rule = [&](double a, double b) {
        const double c = 0.5 * (a + b), h = 0.5 * (b - a), fc = f(c);
        double k = wk[7] * fc, g = wg[3] * fc;
        for (int j = 0; j < 7; ++j) {
            const double pair = f(c - h * xk[j]) + f(c + h * xk[j]);
            k += wk[j] * pair;
            if (j % 2 == 1) g += wg[j / 2] * pair;
        }
        return Interval{a, b, k * h, std::abs(k - g) * h};
    };
    std::priority_queue<Interval> heap;
    double value = 0, error = 0;
    for (std::size_t e = 0; e + 1 < edges.size(); ++e) heap.push(rule(edges[e], edges[e + 1]));
    auto sums = [&] {
        std::priority_queue<Interval> copy = heap;
        value = error = 0;
        while (!copy.empty()) {
            value += copy.top().value;
            error += copy.top().error;
            copy.pop();
        }
    };
    sums();
    while (error > rel_tol * std::abs(value) && heap.size() < max_intervals) {
        const Interval w = heap.top();
        heap.pop();
        const double m = 0.5 * (w.a + w.b);
        const Interval l = rule(w.a, m), r = rule(m, w.b);
        value += l.value + r.value - w.value;
        error += l.error + r.error - w.error;
        heap.push(l);
        heap.push(r);
    }
    sums();
    return value;
}

// Edges of [lo, hi] cut geometrically (ratio 8, down to 1e-12) on both sides of each point in `toward`.
inline std::vector<double> graded_edges(double lo, double hi, const std::vector<double>& toward) {
    std::vector<double> e{lo, hi};
    for (double c : toward) {
        if (c > lo && c < hi) e.push_back(c);
        for (double d = 1.0; d > 1e-12; d *= 0.125) {
            if (c - d > lo && c - d < hi) e.push_back(c - d);
            if (c + d > lo && c + d < hi) e.push_back(c + d);
        }
    }
    std::sort(e.begin(), e.end());
    e.erase(std::unique(e.begin(), e.end()), e.end());
    return e;
}

inline double hemisphere_albedo(const Bsdf& bsdf, double theta_i, double lambda_nm, double rel_tol = 1e-7,
                                std::size_t inner_intervals = 300, std::size_t outer_intervals = 500) {
    const Vec3 wi(std::sin(theta_i), 0.0, std::cos(theta_i));
    const auto theta_edges = graded_edges(0.0, 0.5 * kPi, {theta_i, 0.5 * kPi});
    const auto psi_edges = graded_edges(0.0, kPi, {0.0});
    const double scatter = nested_kronrod(
        [&](double theta) {
            const double st = std::sin(theta), ct = std::cos(theta);
            const double arc = nested_kronrod(
                [&](double psi) {  // phi_o = pi - psi: psi = 0 is the specular plane
                    return bsdf.eval(wi, Vec3(-st * std::cos(psi), st * std::sin(psi), ct), lambda_nm);
                },
                psi_edges, 0.01 * rel_tol, inner_intervals);
            return 2.0 * st * ct * arc;
        },
        theta_edges, rel_tol, outer_intervals);
    return scatter + bsdf.delta_reflectance(wi, lambda_nm);
}

inline double ggx_slope_albedo(double alpha, double theta_i, double rel_tol = 1e-8) {
    const double s = std::sin(theta_i), c = std::cos(theta_i);
    auto smith_lambda = [&](double cos_t) {
        const double t2 = (1.0 - cos_t * cos_t) / (cos_t * cos_t);
        return 0.5 * (std::sqrt(1.0 + alpha * alpha * t2) - 1.0);
    };
    const double lambda_i = smith_lambda(c);
    return nested_kronrod(
        [&](double beta) {
            const double r = std::tan(beta);
            // P22 r dr in beta: sin(beta) cos(beta) / pi.
            const double radial = std::sin(beta) * std::cos(beta) / kPi;
            const double arc = nested_kronrod(
                [&](double phi) {
                    const double px = alpha * r * std::cos(phi), py = alpha * r * std::sin(phi);
                    const double visible = c - s * px;  // (i . m) / m_z with m ~ (-px, -py, 1)
                    if (visible <= 0) return 0.0;
                    const double norm = 1.0 / std::sqrt(1.0 + px * px + py * py);
                    const double im = visible * norm;                // i . m
                    const double oz = 2.0 * im * norm - c;           // o = 2 (i.m) m - i
                    if (oz <= 0) return 0.0;
                    return visible / c / (1.0 + lambda_i + smith_lambda(oz));
                },
                graded_edges(0.0, kPi, {0.0, 0.5 * kPi}), 0.01 * rel_tol);
            return 2.0 * radial * arc;
        },
        graded_edges(0.0, 0.5 * kPi, {0.5 * kPi}), rel_tol);
}

}  // namespace surfscatter::bsdf::test
