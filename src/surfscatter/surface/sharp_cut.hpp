#pragma once
// The low- and high-pass parts of a PSD cut sharply at zeta_c (THEORY.md 3.2), as exact statistics:
//   P_LP = P [zeta <= zeta_c],  P_HP = P [zeta > zeta_c],  sigma_LP^2 = sigma^2 F_c,  sigma_HP^2 = sigma^2 (1 - F_c),
// F_c = F(zeta_c) the base's radial CDF. psd_unit and radial_cdf follow from the base's closed forms. The ACVs come
// from the finite Hankel integral over the disc, D(r) = 2 pi int_0^zeta_c P-hat(zeta) J0(zeta r) zeta dzeta:
//   rho_LP = D / F_c,   rho_HP = (rho - D) / (1 - F_c)
// (rho the base's ACV), never from a transform of the discontinuous P-hat_HP, which rings (Gibbs) at every r.
// D(r) by composite Gauss-Legendre (10 points per panel; panels graded geometrically toward the base's knee
// zeta ~ 1/L and at most half a period of J0(zeta_c r x) wide) while omega = zeta_c r <= 1000; beyond, by the
// edge expansion D = 2 pi zeta_c^2 sum_{n<=4} c_n 2^n n! J_{n+1}(omega) / omega^{n+1} (Sonine's first finite
// integral), c_n the Taylor coefficients of P-hat(zeta_c sqrt(1 - u)) at u = 0 (Chebyshev fit on u in [0, 1/2]).
// The expansion's first neglected term is ~ c_5 3840 omega^-6.5 < 1e-16 c_0 at omega = 1000, so for analytic
// bases (KC, Gaussian ACV) rho_HP and rho_LP are accurate to ~1e-14 absolute / (1 - F_c) (tests/surface/
// test_statistics.cpp, SharpCut.*, against direct quadrature for N = 20, 50, 100, 150 and r from 1e-12 to 1e6 um).
// A base with kinks (TabulatedPsd) keeps its kinks' r^-2 contributions only up to omega = 1000.
// J0 and J_n are glibc's (POSIX j0 / jn, ~35 ns; std::cyl_bessel_j takes ~5 us).
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

enum class CutPart { low_pass, high_pass };

// A part holding less of the variance than this is no part (SharpCutStatistics refuses it; split_psd leaves it out).
inline constexpr double kMinCutFraction = 1e-9;

class SharpCutStatistics final : public RadialStatistics {
public:
    // zeta_c in rad/um; throws Error unless the part keeps at least 1e-9 of the base's variance.
    SharpCutStatistics(std::shared_ptr<const RadialStatistics> base, double zeta_c, CutPart part);

    double sigma_h() const override { return sigma_; }
    double psd_unit(double zeta) const override;
    double acv_normalized(double r) const override;
    double radial_cdf(double zeta) const override;
    double correlation_length() const override { return length_; }
    std::string cache_key() const override;
    double psd_jump_radius() const override { return zeta_c_; }

    double cut() const { return zeta_c_; }
    CutPart part() const { return part_; }
    double disc_integral(double r) const;  // D(r) above; D(0) = F_c (the quadrature's own value)

private:
    std::shared_ptr<const RadialStatistics> base_;
    double zeta_c_;
    CutPart part_;
    double base_cdf_at_cut_;      // F_c from the quadrature rule (D(0)), consistent with disc_integral
    double fraction_;             // F_c (low pass) or 1 - F_c (high pass)
    double sigma_, length_;
    std::vector<double> breaks_;  // panel edges in x = zeta / zeta_c over [0, 1]
    double edge_coefficients_[5];  // 2 pi zeta_c^2 c_n 2^n n!
};

}  // namespace surfscatter::surface
