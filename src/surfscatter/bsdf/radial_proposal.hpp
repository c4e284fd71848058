#pragma once
// A fast, exactly invertible approximation of an isotropic radial distribution, used as the sampling proposal when
// the distribution's own inverse CDF is slow (the S_g table inverts by bisection, ~50 us). Built once from the CDF
// and density at nodes placed uniformly in logit(u) (dense in both tails, u in [1e-10, 1 - 1e-10]): between nodes F
// is the monotone (Fritsch-Carlson) cubic Hermite interpolant in ln(zeta), so the proposal density is continuous and
// within ~1e-4 of the true one; below the first node the density is uniform over the disc, and beyond the last node
// the mass left there (1 - F at that node, at least 1e-12) falls as a power law 1 - F ~ zeta^-a whose density meets
// the last node's (a clamped to [0.5, 8]): the density is positive at every radius, so every direction where the lobe
// is positive can be drawn. Inversion: safeguarded Newton on the cubic. The density it reports is exactly that of
// what it draws, so pdfs stay exact.
#include <cstdint>
#include <functional>
#include <vector>

namespace surfscatter::bsdf {

class RadialProposal {
public:
    // cdf: radial CDF (mass inside radius zeta, -> 1); inverse: its inverse (used only at the nodes);
    // density_2d: the matching density per unit area (used only for the node slopes).
    RadialProposal(const std::function<double(double)>& cdf, const std::function<double(double)>& inverse,
                   const std::function<double(double)>& density_2d);
    double cdf(double zeta) const;          // proposal CDF, in [0, 1]
    double inverse(double u) const;         // radius with cdf = u, u in [0, 1)
    double density_2d(double zeta) const;   // per unit area of the zeta plane

private:
    std::size_t segment(double log_zeta) const;
    std::vector<double> log_zeta_, cdf_, slope_;  // slope_ = dF / d ln(zeta) at the nodes
    double zeta_front_;                           // exp(log_zeta_.front())
    double tail_mass_, tail_power_;               // beyond the last node: 1 - F = tail_mass (zeta/zeta_last)^-power
    std::vector<std::uint16_t> cell_start_;       // see segment()
    double inverse_cell_;
};

}  // namespace surfscatter::bsdf
