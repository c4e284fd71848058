// The paper's refit series (supplemental eqs 1-2) against the exact S_g lobe: relative L1 distance of the scattered
// lobes, int |f_refit - f_exact| cos / int f_exact cos at theta_i = 30 deg, k L = 6.3 (lambda 1 um, L 1 um), perfect
// conductor, both K-renormalised (so both carry the same energy), for gamma 2 .. 4, both truncation rules and g0 from
// 0.1 to 1000. Prints the table of docs/MODELS.md ("Refit against the exact lobe"). About 4 min (the refit K tables at
// g = 1000 sum ~200 orders per evaluation).
// Run: build/bench/table_refit_distance
#include <cmath>
#include <cstdio>

#include "surfscatter/bsdf/factory.hpp"
#include "lobe_distance.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

ModelOptions kc_options(double sigma, double gamma) {
    ModelOptions o;
    o.surface.psd = PsdKind::kc;
    o.surface.sigma = sigma;
    o.surface.corr_length = 1.0;
    o.surface.gamma = gamma;
    return o;
}

}  // namespace

int main() {
    const double lambda = 1000.0, k = wavenumber(lambda);  // k L = 6.3
    std::printf("refit-vs-exact relative L1 lobe distance, theta_i = 30 deg, k L = 6.3 (rows gamma, columns g0)\n");
    std::printf("| gamma | truncation | g=0.1 | g=1 | g=10 | g=100 | g=1000 |\n|---|---|---|---|---|---|---|\n");
    for (double gamma : {2.0, 2.5, 3.0, 4.0})
        for (Truncation truncation : {Truncation::three_sigma, Truncation::poisson_mass}) {
            std::printf("| %g | %s |", gamma, to_string(truncation).c_str());
            for (double g : {0.1, 1.0, 10.0, 100.0, 1000.0}) {
                // sigma giving g0 = (2 k sigma cos theta_i)^2 = g (with sigma_h; sigma_rel is a little smaller)
                auto o = kc_options(std::sqrt(g) / (2 * k * std::cos(30 * kDegree)), gamma);
                const auto exact = make_bsdf(o);
                o.method = GhsMethod::refit;
                o.truncation = truncation;
                const auto refit = make_bsdf(o);
                std::printf(" %.3g |", test::lobe_distance(*refit, *exact, lambda));
                std::fflush(stdout);
            }
            std::printf("\n");
        }
}
