#pragma once
// Self-convolutions of the unit-mass PSD (THEORY.md 1.2, 2.3-2.4): P-hat^{*m}(zeta) = (1/2pi) H0{rho^m}, m = 1..M.
// Each order is a row of radial_table.hpp: ln P-hat^{*m} on a log zeta grid (128 points per decade, one FFTLog
// transform of rho^m with 256 points per decade), cubic interpolation, radial CDF; flat below the grid, and beyond the
// row's window the algebraic tail m P-hat (1 + eps (zeta/zeta_top)^kappa). Accuracy (tests): gamma = 2 against the
// exact KC(L/m) to 7e-9 relative for m <= 200 and zeta*L in [1e-3, 2000]; unit mass of every order to 1e-6;
// Monte-Carlo sums of m Student-t draws match the radial CDF (chi-square). Memory ~20-40 KB per order.
// Built once per (statistics, M) and shared; on-disk cache (radial_table.hpp).
#include <memory>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

class SelfConvolutionTable {
public:
    static std::shared_ptr<const SelfConvolutionTable> get(const RadialStatistics&, int max_order);

    int max_order() const { return max_order_; }
    double eval(int m, double zeta) const;                // P-hat^{*m}(zeta), um^2; m in [1, M]
    double radial_cdf(int m, double zeta) const;          // mass inside |zeta'| <= zeta, in [0, 1]
    double inverse_radial_cdf(int m, double u) const;     // radius (rad/um) for u in [0, 1)

    // Implementation detail shared with the cache loader.
    struct Data;
    explicit SelfConvolutionTable(std::shared_ptr<const Data> data);

private:
    std::shared_ptr<const Data> data_;
    int max_order_;
};

}  // namespace surfscatter::surface
