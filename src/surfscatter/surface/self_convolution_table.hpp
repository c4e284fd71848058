#pragma once
// Self-convolutions of the unit-mass PSD (THEORY.md 1.2, 2.3-2.4): P-hat^{*m}(zeta) = (1/2pi) H0{rho^m}, m = 1..M.
// Each order is stored as ln P-hat^{*m} on a log zeta grid (32 points per decade over zeta*L in [1e-4/..., 1e6],
// cubic interpolation) and its radial CDF; below the grid P-hat^{*m} is flat (relative error < 1e-7), above it a
// power-law tail fitted to the last decade. Accuracy: ~1e-6 relative where P-hat^{*m} > 1e-12 P-hat^{*m}(0).
// Memory ~ 10 KB per order. Built once per (statistics, M) and shared; on-disk cache (scatter_lobe_table.hpp).
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
