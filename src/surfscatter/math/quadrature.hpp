#pragma once
// Adaptive Gauss-Kronrod (7-15) quadrature and fixed Gauss-Legendre rules for smooth 1-D integrals; globally adaptive
// Genz-Malik cubature for 2-D integrals over unions of rectangles.
// Written here (not GSL/Boost) to keep the dependency set to the Debian packages already used; ~60 lines.
#include <functional>
#include <vector>

namespace surfscatter::math {

// int_a^b f(x) dx to |error| <= max(abs_tol, rel_tol |I|) (estimate from the Kronrod-Gauss difference), bisecting
// the interval with the largest error estimate; at most max_intervals subintervals (then returns the best estimate).
double integrate_adaptive(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-10,
                          double abs_tol = 0.0, int max_intervals = 2000);

// A rectangle [x0, x1] x [y0, y1] of a 2-D integration domain; `tag` is handed to the integrand with every point of
// the rectangle and of its subdivisions (the caller's coordinate map for that piece).
struct Box2 {
    double x0, x1, y0, y1;
    int tag = 0;
};
struct Cubature {
    double value = 0, error = 0;  // the estimate and its error estimate (sum over the pieces of |degree 7 - degree 5|)
    long evaluations = 0;
};
// Sum over `boxes` of the integral of f(x, y, tag): Genz-Malik's 17-point rule of degree 7 with its embedded degree-5
// rule on each rectangle, bisecting the rectangle with the largest error estimate along the axis whose fourth
// difference is largest, until the summed error estimate is <= max(abs_tol, rel_tol |I|) or the next bisection would
// exceed max_evaluations. The starting rectangles decide what the rule can see: a feature narrower than them that
// none of their nodes touch is missed, so callers cut them finely where the integrand can be narrow.
Cubature integrate_adaptive_2d(const std::function<double(double x, double y, int tag)>& f, const std::vector<Box2>& boxes,
                               double rel_tol, double abs_tol, long max_evaluations);

// n-point Gauss-Legendre nodes/weights on [-1, 1] (Newton on P_n, accurate to ~1e-15).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);
struct GaussLegendreRule {
    std::vector<double> nodes, weights;
    explicit GaussLegendreRule(int n) { gauss_legendre(n, nodes, weights); }
};

}  // namespace surfscatter::math
