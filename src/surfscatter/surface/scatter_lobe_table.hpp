#pragma once
// The full GHS scatter lobe without any series (THEORY.md 1.2):
//   S_g(zeta) = (1/2pi) H0{exp(-g(1 - rho)) - exp(-g)} = e^{-g} sum_{m>=1} g^m/m! P-hat^{*m}(zeta),
// whose mass over the zeta-plane is 1 - e^{-g}. Tabulated once per statistics as the shape
// s_g = S_g / (1 - e^{-g}) (unit mass), over ln g (8 nodes per decade, g in [1e-4, 1e6]) x ln zeta (grid of
// FFTLog outputs), with bicubic interpolation in (ln g, ln zeta) of ln s_g. For g < 1e-4 the lobe is
// (g P-hat + g^2/2 P-hat^{*2})/(1-e^{-g}) (first two series terms, exact to O(g^2)).
// Accuracy: see docs/SURFACE.md; tested ~1e-6 relative against the Poisson series over zeta*L in [1e-3, 2000].
#include <memory>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

class ScatterLobeTable {
public:
    static constexpr double kMinG = 1e-4;
    static constexpr double kMaxG = 1e6;

    // Built once per statistics (process cache + disk cache under cache_directory()), thread-safe.
    static std::shared_ptr<const ScatterLobeTable> get(const RadialStatistics&);

    double eval(double g, double zeta) const;             // S_g(zeta), um^2; g >= 0 (0 at g = 0); g <= kMaxG
    double shape(double g, double zeta) const;            // S_g / (1 - e^{-g}), unit mass
    double radial_cdf(double g, double zeta) const;       // int_{|zeta'|<=zeta} S_g / (1 - e^{-g})
    double inverse_radial_cdf(double g, double u) const;  // radius for u in [0, 1)

    struct Data;
    explicit ScatterLobeTable(std::shared_ptr<const Data> data);

private:
    std::shared_ptr<const Data> data_;
};

}  // namespace surfscatter::surface
