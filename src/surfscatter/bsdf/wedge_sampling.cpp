#include "surfscatter/bsdf/wedge_sampling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "surfscatter/math/quadrature.hpp"

namespace surfscatter::bsdf {

double wedge_half_angle(double q, double s) {
    if (q <= 1.0 - s) return kPi;
    if (q >= 1.0 + s) return 0.0;
    const double c = (q * q + s * s - 1.0) / (2.0 * q * s);
    return std::acos(std::clamp(c, -1.0, 1.0));
}

std::optional<Vec3> wedge_direction(const Vec3& wi, double q, double u) {
    const double s = sin_theta(wi);
    const double phi_max = wedge_half_angle(q, s);
    if (!(phi_max > 0)) return std::nullopt;
    const double phi_i = s > 0 ? std::atan2(wi.y, wi.x) : 0.0;
    const double phi = phi_i + (2.0 * u - 1.0) * phi_max;
    const double ox = q * std::cos(phi) - wi.x, oy = q * std::sin(phi) - wi.y;
    const double z2 = 1.0 - ox * ox - oy * oy;
    if (!(z2 > 0)) return std::nullopt;
    return Vec3(ox, oy, std::sqrt(z2));
}

double wedge_pdf(double k, double cos_theta_o, double density_2d, double phi_max) {
    if (!(phi_max > 0) || cos_theta_o <= 0) return 0.0;
    return k * k * cos_theta_o * kPi * density_2d / phi_max;
}

DiscIntegral integrate_disc_adaptive(double s, double ci,
                                     const std::function<double(double q, double phi, double cos2_theta_o)>& f,
                                     double rel_tol, double q_jump) {
    constexpr double kEndFraction = 1e-12;  // how close to its end each piece's logarithm reaches, relative to its width
    constexpr double kLogStep = 1.0;        // starting rectangles at most this long in each piece's logarithm
    constexpr long kMaxEvaluations = 4'000'000;
    struct Piece {  // q = anchor + direction e^u for u in [u_lo, u_hi]
        double anchor, direction, u_lo, u_hi;
    };
    const double q_in = ci * ci / (1.0 + s);  // 1 - s without cancellation
    const double q_min = 1e-12 * ci * ci;
    const bool inner = q_in > 2.0 * q_min;
    std::vector<Piece> pieces;
    // The ring left out next to q_in must be thin against the lobe, which can be as narrow as q_in itself (f ~ 1e14 /sr
    // for GGX alpha 1e-4 at 89.99 deg: a ring 1e-12 wide there held 2.6e-5 of the albedo).
    auto add = [&](double anchor, double direction, double width, double closest) {
        if (width > 0) pieces.push_back({anchor, direction, std::log(closest), std::log(width)});
    };
    const double near_q_in = kEndFraction * std::max(std::min(q_in, s), q_min);
    if (inner) {
        pieces.push_back({0.0, 1.0, std::log(q_min), std::log(0.5 * q_in)});
        add(q_in, -1.0, 0.5 * q_in, near_q_in);
    }
    add(q_in, 1.0, s, near_q_in);
    add(1.0 + s, -1.0, s, kEndFraction * s);
    std::vector<double> w_edges{1.0};
    for (double w = 0.25; w > 0.01 * ci; w *= 0.25) w_edges.push_back(w);
    w_edges.push_back(0.0);
    std::vector<math::Box2> boxes;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        const Piece& piece = pieces[p];
        std::vector<double> u_edges;
        const double lo = piece.u_lo, span = piece.u_hi - lo;
        const int n = std::max(1, int(std::ceil(span / kLogStep)));
        for (int j = 0; j <= n; ++j) u_edges.push_back(lo + span * j / n);
        const double jump_distance = piece.direction * (q_jump - piece.anchor);
        if (q_jump > 0 && jump_distance > 0 && std::log(jump_distance) > lo && std::log(jump_distance) < piece.u_hi)
            u_edges.push_back(std::log(jump_distance));
        std::sort(u_edges.begin(), u_edges.end());
        for (std::size_t j = 0; j + 1 < u_edges.size(); ++j)
            for (std::size_t e = 0; e + 1 < w_edges.size(); ++e)
                boxes.push_back({u_edges[j], u_edges[j + 1], w_edges[e + 1], w_edges[e], int(p)});
    }
    auto at = [&](double q, double phi) {
        const double z2 = ci * ci - q * (q - 2.0 * s * std::cos(phi));
        return z2 > 0 ? f(q, phi, z2) : 0.0;
    };
    const math::Cubature c = math::integrate_adaptive_2d(
        [&](double u, double w, int tag) {
            const Piece& p = pieces[std::size_t(tag)];
            const double e = std::exp(u), q = p.anchor + p.direction * e;
            const double phi_max = wedge_half_angle(q, s);
            return 2.0 * q * e * 2.0 * phi_max * w * at(q, phi_max * (1.0 - w * w));  // both halves, q, dq/du, dphi/dw
        },
        boxes, rel_tol, 0.0, kMaxEvaluations);
    DiscIntegral r{c.value, c.error, c.evaluations};
    if (inner) {
        r.value += kPi * q_min * q_min * at(0.0, 0.0);
        ++r.evaluations;
    }
    return r;
}

}  // namespace surfscatter::bsdf
