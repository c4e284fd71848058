#pragma once
// An independent computation of the two-scale model's micro (diffraction) lobe for a KC surface cut sharply at
// zeta_c (THEORY 1.1-1.2, 3.2), by quadrature only: no FFTLog, no lobe table and no statistics class of the library.
//   * rho_HP(r) = (rho_KC(r) - D(r)) / (1 - F_c) with rho_KC in closed form (its r -> 0 behaviour makes the lobe's
//     far tail) and D(r) = 2 pi int_0^zeta_c P-hat J0(zeta r) zeta dzeta by a fixed Gauss-Legendre rule (8 nodes on each
//     of zeta_c R / pi + 4 panels) on a uniform r grid (step min(L, 1/zeta_c)/32 up to R = 100 / zeta_c), cubic in
//     between (D holds no frequency above zeta_c);
//   * S_g(zeta) = g e^{-g} P-hat_HP(zeta) + (1/2pi) int_0^R e^{-g} (e^{g rho} - 1 - g rho) J0(zeta r) r dr (the orders
//     m >= 2, 8-node Gauss-Legendre panels no wider than min(4 steps, pi / zeta_max), a raised-cosine taper over
//     [R/2, R]); for zeta < 4 zeta_c, where the r^-3 decay of rho^2 converges slowly (1 % at zeta = 0), the part the
//     taper removes is integrated on to 1e4 / zeta_c with rho_HP from the first two terms of its large-r expansion
//     (Sonine's integral, int_0^1 (1 - x^2)^n x J0(w x) dx = 2^n n! J_{n+1}(w) / w^{n+1}):
//     rho_HP ~ -2 pi zeta_c^2 (c0 J1(w)/w + 2 c1 J2(w)/w^2) / (1 - F_c), w = zeta_c r, c0 = P-hat(zeta_c),
//     c1 = -zeta_c P-hat'(zeta_c) / 2;
//   * sigma_rel^2 = sigma_HP^2 x the mass of P-hat_HP over the visible disc (polar quadrature about zeta = 0);
//   * K = (1 - e^{-g0}) / int_disc k^2 S_g d^2o_xy, in polar coordinates about the specular point with the azimuth
//     phi = phi_max sin(pi t / 2) (the library uses a different substitution), r truncated at max(10/zeta_c, 30 L)
//     for this mass integral (truncating r only moves mass within the lobe's centre).
// The micro BRDF is then K k^2 S_g(k |i_xy + o_xy|), g = (k sigma_rel (cos i + cos o))^2 (perfect conductor, R = 1).
#include <algorithm>
#include <cmath>
#include <vector>

#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::bsdf::test {

class MicroLobeReference {
public:
    // zeta_max: the largest |zeta| (rad/um) the lobe will be asked for (sets the r quadrature's panel width).
    MicroLobeReference(double sigma, double length, double gamma, double zeta_c, double zeta_max)
        : sigma_(sigma), length_(length), gamma_(gamma), zeta_c_(zeta_c) {
        math::gauss_legendre(8, gx_, gw_);
        fraction_ = std::pow(1.0 + length * length * zeta_c * zeta_c, -0.5 * (gamma - 1.0));
        // rho_HP on the uniform grid.
        step_ = std::min(length, 1.0 / zeta_c) / 32.0;
        r_max_ = 100.0 / zeta_c;
        const int panels = static_cast<int>(zeta_c * r_max_ / kPi) + 4;
        std::vector<double> zeta_nodes, zeta_weights;
        for (int p = 0; p < panels; ++p)
            for (std::size_t i = 0; i < gx_.size(); ++i) {
                const double z = zeta_c * (p + 0.5 + 0.5 * gx_[i]) / panels;
                zeta_nodes.push_back(z);
                zeta_weights.push_back(2.0 * kPi * 0.5 * zeta_c / panels * gw_[i] * phat(z) * z);
            }
        const int n = static_cast<int>(r_max_ / step_) + 4;
        disc_.resize(n);
        for (int j = 0; j < n; ++j) {
            const double r = j * step_;
            double d = 0;
            for (std::size_t i = 0; i < zeta_nodes.size(); ++i) d += zeta_weights[i] * j0(zeta_nodes[i] * r);
            disc_[j] = d;
        }
        // r quadrature nodes for the Hankel integrals.
        const double width = std::min(4.0 * step_, kPi / zeta_max);
        for (double a = 0; a < r_max_; a += width)
            for (std::size_t i = 0; i < gx_.size(); ++i) {
                const double r = a + 0.5 * width * (1.0 + gx_[i]);
                r_.push_back(r);
                // Raised-cosine taper over [R/2, R]: an abrupt end would ring at large zeta (5 % at zeta L = 45).
                const double taper = r < 0.5 * r_max_ ? 1.0 : 0.5 * (1.0 + std::cos(kPi * (2.0 * r / r_max_ - 1.0)));
                r_weight_.push_back(0.5 * width * gw_[i] * r / (2.0 * kPi) * taper);
                r_rho_.push_back(rho_at(r));
            }
    }

    double phat(double z) const {
        return (gamma_ - 1.0) * length_ * length_ / (2.0 * kPi) * std::pow(1.0 + length_ * length_ * z * z, -0.5 * (gamma_ + 1.0));
    }
    double phat_hp(double z) const { return z > zeta_c_ ? phat(z) / fraction_ : 0.0; }
    double sigma_hp() const { return sigma_ * std::sqrt(fraction_); }
    double rho_hp(double r) const { return rho_at(r); }

    // S_g(zeta) with the r integral truncated at r_limit (no far tail then).
    double lobe(double g, double zeta, double r_limit = 1e300) const {
        double sum = 0;
        const double e = std::exp(-g);
        for (std::size_t n = 0; n < r_.size() && r_[n] <= r_limit; ++n)
            sum += r_weight_[n] * remainder(g, e, r_rho_[n]) * j0(zeta * r_[n]);
        if (r_limit > r_max_ && zeta < 4.0 * zeta_c_) sum += far_tail(g, zeta);
        return g * std::exp(-g) * phat_hp(zeta) + sum;
    }

    // sigma_rel (um) and K at incidence theta_i (rad) and wavelength lambda (nm).
    struct Incidence {
        double k, sigma_rel, norm;
    };
    Incidence incidence(double theta_i, double lambda_nm) const {
        const double k = kTwoPi / (lambda_nm * 1e-3), s = std::sin(theta_i), ci = std::cos(theta_i);
        // Visible-disc mass of P-hat_HP: rings |zeta| = z inside the disc over the arc 2 phi_max(z / k).
        const double mass = integrate_in_z(k, s, [&](double z) {
            return 2.0 * phi_max(z / k, s) * z * phat_hp(z);
        });
        const double sigma_rel = sigma_hp() * std::sqrt(mass);
        const double r_limit = std::max(10.0 / zeta_c_, 30.0 * length_);
        // Scattered mass int k^2 S_g d^2 o_xy over the disc (q = |o_xy + i_xy| = zeta / k).
        const double scattered = integrate_in_z(k, s, [&](double z) {
            const double q = z / k, pm = phi_max(q, s);
            if (!(pm > 0)) return 0.0;
            // J0(z r) once for every azimuth node of this ring.
            std::vector<double> jz;
            for (std::size_t n = 0; n < r_.size() && r_[n] <= r_limit; ++n) jz.push_back(r_weight_[n] * j0(z * r_[n]));
            double ring = 0;
            for (std::size_t a = 0; a < gx_.size(); ++a) {
                const double t = 0.5 * (1.0 + gx_[a]);
                const double phi = pm * std::sin(0.5 * kPi * t), dphi = pm * 0.5 * kPi * std::cos(0.5 * kPi * t);
                const double ox = q * std::cos(phi) - s, oy = q * std::sin(phi);
                const double co = std::sqrt(std::max(0.0, 1.0 - ox * ox - oy * oy));
                const double g = std::pow(k * sigma_rel * (ci + co), 2);
                const double e = std::exp(-g);
                double sum = g * e * phat_hp(z);
                for (std::size_t n = 0; n < jz.size(); ++n) sum += jz[n] * remainder(g, e, r_rho_[n]);
                ring += 0.5 * gw_[a] * dphi * sum;
            }
            return 2.0 * ring * z;  // both halves of the wedge; d^2 zeta = z dz dphi
        });
        const double g0 = std::pow(2.0 * k * sigma_rel * ci, 2);
        return {k, sigma_rel, -std::expm1(-g0) / scattered};
    }

    double brdf(const Incidence& in, const Vec3& wi, const Vec3& wo) const {
        const double x = wi.x + wo.x, y = wi.y + wo.y;
        const double g = std::pow(in.k * in.sigma_rel * (wi.z + wo.z), 2);
        return in.norm * in.k * in.k * lobe(g, in.k * std::sqrt(x * x + y * y));
    }

private:
    // (1/2pi) int_{R/2}^{1e4/zeta_c} (1 - taper) e^{-g}(e^{g rho} - 1 - g rho) J0(zeta r) r dr, rho from the expansion.
    double far_tail(double g, double zeta) const {
        const double a = zeta_c_ * length_, p = phat(zeta_c_);
        const double c0 = p, c1 = 0.5 * zeta_c_ * p * (gamma_ + 1.0) * length_ * a / (1.0 + a * a);
        const double e = std::exp(-g), width = kPi / (2.0 * std::max(zeta, zeta_c_));
        double sum = 0;
        for (double lo = 0.5 * r_max_; lo < 1e4 / zeta_c_; lo += width)
            for (std::size_t i = 0; i < gx_.size(); ++i) {
                const double r = lo + 0.5 * width * (1.0 + gx_[i]), w = zeta_c_ * r;
                const double taper = r < r_max_ ? 0.5 * (1.0 - std::cos(kPi * (2.0 * r / r_max_ - 1.0))) : 1.0;
                const double rho = -2.0 * kPi * zeta_c_ * zeta_c_ * (c0 * j1(w) / w + 2.0 * c1 * jn(2, w) / (w * w)) / fraction_;
                sum += 0.5 * width * gw_[i] * taper * remainder(g, e, rho) * j0(zeta * r) * r;
            }
        return sum / (2.0 * kPi);
    }
    double rho_kc(double r) const {
        const double x = r / length_, nu = 0.5 * (gamma_ - 1.0);
        if (x == 0) return 1.0;
        return std::pow(2.0, 1.0 - nu) / std::tgamma(nu) * std::pow(x, nu) * std::cyl_bessel_k(nu, x);
    }
    double rho_at(double r) const {
        const double t = r / step_;
        const int i = std::clamp(static_cast<int>(t), 1, static_cast<int>(disc_.size()) - 3);
        const double u = t - i;
        const double d = disc_[i - 1] * (-u * (u - 1) * (u - 2) / 6) + disc_[i] * ((u + 1) * (u - 1) * (u - 2) / 2) +
                         disc_[i + 1] * (-(u + 1) * u * (u - 2) / 2) + disc_[i + 2] * ((u + 1) * u * (u - 1) / 6);
        return (rho_kc(r) - d) / fraction_;
    }
    // e^{-g} (e^{g rho} - 1 - g rho), exp_minus_g = e^{-g}
    static double remainder(double g, double exp_minus_g, double rho) {
        const double x = g * rho;
        if (std::abs(x) < 1e-3) return exp_minus_g * x * x * (0.5 + x / 6.0 + x * x / 24.0);
        if (g < 30) return exp_minus_g * (std::expm1(x) - x);
        return std::exp(-g * (1.0 - rho)) - exp_minus_g * (1.0 + x);
    }
    // Arc half-angle of the ring |zeta| = q k inside the visible disc (law of cosines).
    static double phi_max(double q, double s) {
        if (q <= 1.0 - s) return kPi;
        if (q >= 1.0 + s) return 0.0;
        return std::acos(std::clamp((q * q + s * s - 1.0) / (2.0 * q * s), -1.0, 1.0));
    }
    // int_0^{k(1+s)} f(z) dz: 8-node panels, geometric (ratio 1.5) from 1e-4 zeta_c, with edges at zeta_c and at the
    // circles k(1 -+ s) where phi_max has square-root kinks (approached geometrically from both sides).
    template <typename F>
    double integrate_in_z(double k, double s, F f) const {
        const double z_end = k * (1.0 + s), z_inner = k * (1.0 - s);
        std::vector<double> edges{0.0, zeta_c_, z_end, z_inner};
        for (double z = 1e-4 * zeta_c_; z < z_end; z *= 1.5) edges.push_back(z);
        for (int j = 1; j <= 16; ++j) {
            const double d = 2.0 * k * s * std::ldexp(1.0, -j);
            edges.push_back(z_end - d);
            edges.push_back(z_inner + d);
            edges.push_back(z_inner - d);
        }
        std::sort(edges.begin(), edges.end());
        edges.erase(std::remove_if(edges.begin(), edges.end(), [&](double z) { return z < 0.0 || z > z_end; }),
                    edges.end());
        edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
        double total = 0;
        for (std::size_t e = 0; e + 1 < edges.size(); ++e) {
            const double a = edges[e], b = edges[e + 1];
            for (std::size_t i = 0; i < gx_.size(); ++i) total += 0.5 * (b - a) * gw_[i] * f(0.5 * (a + b) + 0.5 * (b - a) * gx_[i]);
        }
        return total;
    }

    double sigma_, length_, gamma_, zeta_c_, fraction_, step_, r_max_;
    std::vector<double> gx_, gw_, disc_, r_, r_weight_, r_rho_;
};

}  // namespace surfscatter::bsdf::test
