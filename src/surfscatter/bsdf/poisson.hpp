#pragma once
// Poisson orders for the GHS series. The BSDF interface hands the sampler a fixed set of uniforms, so orders are
// drawn by inversion of the CDF with ONE uniform (exact for every mean, no underflow: the pmf is evaluated in log
// space over a window of the kept orders) instead of Knuth's product method (unbounded number of uniforms, O(mean),
// underflows near mean 700) or PTRS (rejection, also unbounded).
#include <vector>

namespace surfscatter::bsdf {

double poisson_pmf(int m, double mean);

// The Poisson(mean) distribution restricted to the orders [first, last] and renormalised over them.
class PoissonWindow {
public:
    PoissonWindow(double mean, int first, int last);
    // Orders within `sigmas` standard deviations of the mean (at least first_min), the paper's 3-sigma rule.
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
