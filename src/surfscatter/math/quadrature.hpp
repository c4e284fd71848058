#pragma once
// Adaptive Gauss-Kronrod (7-15) quadrature and fixed Gauss-Legendre rules for smooth 1-D integrals.
// Written here (not GSL/Boost) to keep the dependency set to the Debian packages already used; ~60 lines.
#include <functional>
#include <vector>

namespace surfscatter::math {

// int_a^b f(x) dx to |error| <= max(abs_tol, rel_tol |I|) (estimate from the Kronrod-Gauss difference), bisecting
// the interval with the largest error estimate; at most max_intervals subintervals (then returns the best estimate).
double integrate_adaptive(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-10,
                          double abs_tol = 0.0, int max_intervals = 2000);

// n-point Gauss-Legendre nodes/weights on [-1, 1] (Newton on P_n, accurate to ~1e-15).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);
struct GaussLegendreRule {
    std::vector<double> nodes, weights;
    explicit GaussLegendreRule(int n) { gauss_legendre(n, nodes, weights); }
};

}  // namespace surfscatter::math
