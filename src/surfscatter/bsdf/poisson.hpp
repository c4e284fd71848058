#pragma once
// Poisson orders for the GHS series. The BSDF interface hands the sampler a fixed set of uniforms, so orders are
// drawn by inversion of the CDF with ONE uniform (exact for every mean, no underflow: the pmf is evaluated in log
// space over a window of the kept orders) instead of Knuth's product method (unbounded number of uniforms, O(mean),
// underflows near mean 700) or PTRS (rejection, also unbounded).
#include <vector>

namespace surfscatter::bsdf {

double poisson_pmf(int m, double mean);

// The Poisson(mean) distribution restricted to the orders [first, last], the end orders weighted by first_factor and
// last_factor in [0, 1], and renormalised over them.
class PoissonWindow {
public:
    PoissonWindow(double mean, int first, int last, double first_factor = 1.0, double last_factor = 1.0);
    // Orders within `sigmas` standard deviations of the mean (at least first_min, always whole), the paper's 3-sigma
    // rule, made continuous in the mean: an order at the window's edge enters with the fraction of its unit interval
    // [m - 1, m] (upper edge) or [m, m + 1] (lower edge) inside mean +- sigmas sd; the kept orders are the integer
    // rule's whenever mean +- sigmas sd is an integer. With whole orders entering at once, a narrow lobe's mass (near
    // g = g0) changed abruptly with the incidence: K by 3.2 % within 0.1 deg where order 2 enters (g0 = 0.315), and
    // the cubic through K's incidence nodes put the albedo 0.84 % off (tests: Refit.SmoothWhereAnOrderEnters...).
    static PoissonWindow within_sigmas(double mean, double sigmas, int first_min);
    // Smallest window [first_min, last] (plus the lower tail cut at the same epsilon) holding all but epsilon of
    // the Poisson mass above first_min.
    static PoissonWindow by_mass(double mean, double epsilon, int first_min);

    int first() const { return first_; }
    int last() const { return first_ + int(weights_.size()) - 1; }
    double weight(int m) const;          // renormalised probability of order m (0 outside the window)
    double kept_mass() const { return kept_mass_; }  // Poisson mass of the window before renormalisation
    int sample(double u) const;          // u in [0, 1)

private:
    int first_;
    std::vector<double> weights_, cdf_;
    double kept_mass_ = 0;
};

// An unrestricted Poisson(mean) draw from one uniform u in [0, 1) (window of +-9 sd + 12, dropped mass < 1e-15).
int sample_poisson(double mean, double u);

}  // namespace surfscatter::bsdf
