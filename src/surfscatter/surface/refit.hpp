#pragma once
// The supplemental's refit (THEORY.md 2.4): each P-hat^{*m} is fitted by a KC of the same gamma and free L_m
// (least squares of ln P over ln zeta, weighted by the mass element P-hat^{*m} zeta d zeta, i.e. the "mass-weighted
// log fit"), then L_m = L m^-x by least squares of ln L_m on ln m over m = 1..M.
#include <vector>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

struct RefitResult {
    double exponent_x = 0;                // x of L_m = L m^-x
    std::vector<double> corr_length_m;    // L_m (um), index m-1
    std::vector<double> misfit_m;         // int |fit - true| d2zeta (fraction of unit mass), index m-1
};

// The orders a user may ask for (selfconv --orders, Python's refit and self_convolution): the table of 5000 orders
// takes minutes to build; more is not a request anyone means.
inline constexpr int kMaxRefitOrders = 5000;
// Throws Error "<what> must be in [1, 5000], got <orders>" outside that range.
void require_refit_orders(long long orders, const char* what);

RefitResult refit_self_convolutions(const KCorrelation&, int max_order);

}  // namespace surfscatter::surface
