#pragma once
// The sum behind every far field of a profile (exact_1d.hpp's FarField and the statistical mode's Kirchhoff
// control): on theta = -90, -89.9, ..., 90 deg (kFarFieldSteps + 1 directions),
//   S(theta) = sum_j (a_j + cos(theta) b_j - sin(theta) c_j) exp(-i k (x_j sin(theta) + h_j cos(theta))),
// x_j = x0 + j step. Relative rounding ~n eps (docs/REFERENCE.md, "Solve").
#include <complex>
#include <vector>

namespace surfscatter::reference {

// b and c empty: zero. Otherwise a, b, c and h all of the same size (>= 1).
std::vector<std::complex<double>> far_field_sum(double k_per_um, double x0_um, double step_um,
                                                const std::vector<double>& h_um,
                                                const std::vector<std::complex<double>>& a,
                                                const std::vector<std::complex<double>>& b,
                                                const std::vector<std::complex<double>>& c);

}  // namespace surfscatter::reference
