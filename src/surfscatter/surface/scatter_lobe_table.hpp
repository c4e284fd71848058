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
#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/math/simd_pair.hpp"
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
    // ln eval_at_logs without its exponential. Inline: the exact GHS eval's bicubic, for g in [kMinG, kMaxG] and zeta
    // inside the stencil rows' nodes of a PSD without a jump; elsewhere out of line.
    double log_eval_at_logs(double log_g, double log_zeta) const {
        double value;
        return !data_has_first_order_ && interior_log_value(log_g, log_zeta, true, value)
                   ? value
                   : log_eval_outside(log_g, log_zeta);
    }
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
    double lobe_log_value(double log_g, double log_zeta, bool with_mass) const;
    double lobe_log_value_by_rows(double log_g, double log_zeta, bool with_mass) const;
    double log_eval_outside(double log_g, double log_zeta) const;
    bool interior_log_value(double log_g, double log_zeta, bool with_mass, double& value) const;
    // Position of ln g among the g rows' nodes, (ln g - ln kMinG) / step: >= 0 up to rounding for g >= kMinG.
    double g_position(double log_g) const { return (log_g - grid_.log_g_min) * grid_.inv_g_step; }
    // The first of the stencil's rows first .. first+3 (nodes first-1 .. first+2; row 0 is the g -> 0 limit) at
    // position t in [0, g_position_max] (truncation is floor there); t - first is the stencil's fractional position.
    int stencil_first(double t) const { return std::clamp(static_cast<int>(t), 1, grid_.last_first); }
    struct Stencil {
        int first;
        std::array<double, 4> w;
    };
    Stencil stencil(double log_g) const;  // rows and cubic weights for ln g in [ln kMinG, ln kMaxG]

    // What the inline bicubic reads, flat in the object (no pointer chase through data_).
    struct Grid {
        double log_g_min, inv_g_step, g_position_max;  // row stencils: position (ln g - log_g_min) * inv_g_step
        int last_first;                                // the last stencil's first row
        double log_zeta0, inv_zeta_step;               // the rows' stored zeta grid
        std::vector<const double*> rows;               // row r's ln values from stored index 0
        // For the stencil starting at row r: the fractional zeta position below which all four rows r .. r+3 are
        // interpolated from their own interior nodes (same zeta weights for all four), min over the rows of n - 2.
        std::vector<double> shared_interior_end;
        std::vector<double> log_mass;  // ln of each row's mass, 1 - e^{-g} or remainder_mass(g) (row 0: unused)
    };
    std::shared_ptr<const Data> data_;
    bool data_has_first_order_;  // data_->first_order set, read by the inline path without the pointer chase
    Grid grid_;
};

namespace detail {
// Cubic Lagrange weights for nodes -1, 0, 1, 2 at two fractional positions u (lane by lane, as cubic_interpolate).
inline std::array<math::Pair, 4> cubic_weights(math::Pair u) {
    const math::Pair um = u - 1.0, up = u + 1.0, u2 = u - 2.0, a = u * um;
    return {a * u2 * (-1.0 / 6.0), up * um * u2 * 0.5, up * u * u2 * -0.5, a * up * (1.0 / 6.0)};
}
}  // namespace detail

// Bicubic ln s_g(zeta), plus the cubic interpolation of ln(1 - e^{-g}) when with_mass (ln S_g), over rows first ..
// first+3 (nodes first-1 .. first+2; row 0 is the g -> 0 limit). Every row starts at stored index 0 (make_row), so
// where zeta lies inside all four rows' nodes one set of zeta weights serves the 4 x 4 stencil, g and zeta weights and
// pairs of taps computed in SSE2 lanes. False (value untouched) outside [kMinG, kMaxG] or those nodes.
inline bool ScatterLobeTable::interior_log_value(double log_g, double log_zeta, bool with_mass, double& value) const {
    using math::Pair;
    const double t = g_position(log_g);
    if (!(t >= 0.0 && t <= grid_.g_position_max)) return false;
    const int first = stencil_first(t);
    const double tz = (log_zeta - grid_.log_zeta0) * grid_.inv_zeta_step;
    if (!(tz > 0.0 && tz < grid_.shared_interior_end[first])) return false;
    const int j = std::max(static_cast<int>(tz), 1) - 1;  // tz < 1: the first four nodes, as cubic_interpolate
    const std::array<Pair, 4> w = detail::cubic_weights(Pair{t - first, tz - (j + 1)});  // lane 0: g, lane 1: zeta
    const Pair wz01 = {w[0][1], w[1][1]}, wz23 = {w[2][1], w[3][1]};
    std::array<Pair, 4> row;
    for (int i = 0; i < 4; ++i) {
        const double* y = grid_.rows[first + i] + j;
        row[i] = w[i][0] * (math::load_pair(y) * wz01 + math::load_pair(y + 2) * wz23);
    }
    Pair sum = (row[0] + row[1]) + (row[2] + row[3]);  // a tree: this sum is on the critical path
    if (with_mass) {
        const double* m = grid_.log_mass.data() + first;
        sum += math::load_pair(m) * Pair{w[0][0], w[1][0]} + math::load_pair(m + 2) * Pair{w[2][0], w[3][0]};
    }
    value = sum[0] + sum[1];
    return true;
}

}  // namespace surfscatter::surface
