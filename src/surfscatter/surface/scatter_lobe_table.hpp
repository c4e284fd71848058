#pragma once
// The full GHS scatter lobe without any series (THEORY.md 1.2):
//   S_g(zeta) = (1/2pi) H0{exp(-g(1 - rho)) - exp(-g)} = e^{-g} sum_{m>=1} g^m/m! P-hat^{*m}(zeta),
// whose mass over the zeta-plane is 1 - e^{-g}. Generic over RadialStatistics (KC, Gaussian ACV, high-pass parts).
// Tabulated once per statistics as the unit-mass shape s_g = S_g / (1 - e^{-g}): rows at g -> 0 (= P-hat) and at
// 48 log-spaced g per decade over [1e-4, 1e6]; each row is ln s_g on a log zeta grid (128 points per decade, covering
// zeta from ~1e-4/L up to where the row has decayed; see radial_table.hpp) with its radial CDF. Lookup: cubic
// Lagrange in ln zeta and across the 4 nearest g rows (in ln g), with one set of zeta weights for all four rows inside
// their nodes; g < 1e-4 linear in g between the g -> 0 row and the first node (error O(g^2)). Beyond a row's zeta
// window the tail is c P-hat (1 + eps (zeta/zeta_top)^kappa), the algebraic asymptotics S_g -> g P-hat of the m = 1
// term, so every zeta (up to 1e300) gives a finite value.
// A PSD with a jump (psd_jump_radius() > 0: the high-pass part of a sharp cut, SharpCutStatistics) would make the
// transform ring and the rows end inside the hole zeta < zeta_c; there the first-order term g e^{-g} P-hat, which
// carries the jump, is added exactly at every lookup and only the orders m >= 2 are tabulated (a continuous function:
// P-hat^{*2} of a disc-less PSD has no jump), as rows of their unit-mass shape with mass 1 - e^{-g} - g e^{-g}, the
// g -> 0 row being P-hat^{*2} = (1/2pi) H0{rho^2}, the tail weight g (1 - e^{-g}); radial CDFs combine the two parts.
// Accuracy (tests, KC gamma 2.5 and 3, zeta*L in [1e-3, 2000], g in [1e-5, 42] incl. between nodes): |S_g / series
// - 1| < 4e-7 against e^{-g} sum g^m/m! P-hat^{*m}; unit mass to < 1e-5 for every g including gamma = 1.5 and the
// Gaussian ACV; high-pass parts of KC (N = 20 .. 150) within 1e-4 of an independent Hankel quadrature of the ACV
// (tests/bsdf/test_two_scale.cpp) and every row's CDF at 1 within 1e-5 (tests/surface/test_tables.cpp).
// Building: ~0.1-0.3 s per statistics (docs/SURFACE.md), then cached on disk.
#include <memory>
#include <string>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

class ScatterLobeTable {
public:
    static constexpr double kMinG = 1e-4;
    static constexpr double kMaxG = 1e6;

    // Built once per statistics (process cache + disk cache under cache_directory()), thread-safe.
    static std::shared_ptr<const ScatterLobeTable> get(std::shared_ptr<const RadialStatistics>);

    double eval(double g, double zeta) const;             // S_g(zeta), um^2; g in [0, kMaxG] (else Error); 0 at g = 0
    // S_g(zeta) from ln g and ln zeta, as the BSDF has them (its hot path: no logarithm of its own); g above kMaxG
    // is evaluated at kMaxG. For g in [kMinG, kMaxG] the factor 1 - e^{-g} is interpolated with the rows (cubic in
    // ln g; relative error < 1e-7, the rest as eval); below, eval(e^{log_g}, e^{log_zeta}).
    double eval_at_logs(double log_g, double log_zeta) const;
    double log_eval_at_logs(double log_g, double log_zeta) const;  // ln eval_at_logs, without its exponential
    double shape(double g, double zeta) const;            // S_g / (1 - e^{-g}), unit mass
    double radial_cdf(double g, double zeta) const;       // int_{|zeta'|<=zeta} S_g / (1 - e^{-g})
    // Radius for u in [0, 1): the interpolated radial_cdf inverted to 1e-13 in ln zeta (safeguarded Newton).
    double inverse_radial_cdf(double g, double u) const;
    // What the table's values depend on (statistics, grid, construction version): a key for tables derived from it.
    const std::string& key() const;

    struct Data;
    explicit ScatterLobeTable(std::shared_ptr<const Data> data);

private:
    double rows_shape(double g, double zeta) const;  // the tabulated rows' unit-mass shape, interpolated in g
    std::shared_ptr<const Data> data_;
};

}  // namespace surfscatter::surface
