#include "surfscatter/material/lorentz_drude.hpp"

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/wavelength_check.hpp"
#include "surfscatter/spectrum/physical_constants.hpp"

namespace surfscatter::material {

const std::vector<LorentzDrudeParameters>& rakic1998_lorentz_drude() {
    // wp, f0, g0; oscillators (f_j, g_j, w_j); fit range in eV as tabulated by the refractiveindex.info database.
    static const std::vector<LorentzDrudeParameters> metals = {
        {"Ag", 9.01, 0.845, 0.048,
         {{0.065, 3.886, 0.816}, {0.124, 0.452, 4.481}, {0.011, 0.065, 8.185}, {0.84, 0.916, 9.083},
          {5.646, 2.419, 20.29}}, 0.1, 5.0},
        {"Al", 14.98, 0.523, 0.047,
         {{0.227, 0.333, 0.162}, {0.05, 0.312, 1.544}, {0.166, 1.351, 1.808}, {0.03, 3.382, 3.473}}, 0.005, 20.0},
        {"Au", 9.03, 0.76, 0.053,
         {{0.024, 0.241, 0.415}, {0.01, 0.345, 0.83}, {0.071, 0.87, 2.969}, {0.601, 2.494, 4.304},
          {4.384, 2.214, 13.32}}, 0.2, 5.0},
        {"Be", 18.51, 0.084, 0.035,
         {{0.031, 1.664, 0.1}, {0.14, 3.395, 1.032}, {0.53, 4.454, 3.183}, {0.13, 1.802, 4.604}}, 0.02, 5.0},
        {"Cr", 10.75, 0.168, 0.047,
         {{0.151, 3.175, 0.121}, {0.15, 1.305, 0.543}, {1.149, 2.676, 1.97}, {0.825, 1.335, 8.775}}, 0.02, 5.0},
        {"Cu", 10.83, 0.575, 0.03,
         {{0.061, 0.378, 0.291}, {0.104, 1.056, 2.957}, {0.723, 3.213, 5.3}, {0.638, 4.305, 11.18}}, 0.1, 6.0},
        {"Ni", 15.92, 0.096, 0.048,
         {{0.1, 4.511, 0.174}, {0.135, 1.334, 0.582}, {0.106, 2.178, 1.597}, {0.729, 6.292, 6.089}}, 0.2, 5.0},
        {"Pd", 9.72, 0.33, 0.008,
         {{0.649, 2.95, 0.336}, {0.121, 0.555, 0.501}, {0.638, 4.621, 1.659}, {0.453, 3.236, 5.715}}, 0.1, 5.0},
        {"Pt", 9.59, 0.333, 0.08,
         {{0.191, 0.517, 0.78}, {0.659, 1.838, 1.314}, {0.547, 3.668, 3.141}, {3.576, 8.517, 9.249}}, 0.1, 5.0},
        {"Ti", 7.29, 0.148, 0.082,
         {{0.899, 2.276, 0.777}, {0.393, 2.518, 1.545}, {0.187, 1.663, 2.509}, {0.001, 1.762, 19.43}}, 0.04, 5.0},
        {"W", 13.22, 0.206, 0.064,
         {{0.054, 0.53, 1.004}, {0.166, 1.281, 1.917}, {0.706, 3.332, 3.58}, {2.59, 5.836, 7.498}}, 0.1, 5.0},
    };
    return metals;
}

std::complex<double> lorentz_drude_permittivity(const LorentzDrudeParameters& p, double photon_energy_eV) {
    using C = std::complex<double>;
    const double e = photon_energy_eV;
    const double wp2 = p.plasma_energy * p.plasma_energy;
    C eps = 1.0 - p.drude_strength * wp2 / (e * C(e, p.drude_damping));
    for (const auto& o : p.oscillators) eps += o.strength * wp2 / C(o.energy * o.energy - e * e, -e * o.damping);
    return eps;
}

std::complex<double> index_from_permittivity(std::complex<double> permittivity) {
    // std::sqrt takes the principal root (Re >= 0); with Im(eps) >= 0 that root also has Im >= 0.
    const std::complex<double> n = std::sqrt(permittivity);
    return n.imag() < 0 ? -n : n;
}

LorentzDrudeIndex::LorentzDrudeIndex(LorentzDrudeParameters parameters) : parameters_(std::move(parameters)) {}

double LorentzDrudeIndex::min_wavelength_nm() const { return spectrum::kPhotonEnergyNm / parameters_.max_energy; }
double LorentzDrudeIndex::max_wavelength_nm() const { return spectrum::kPhotonEnergyNm / parameters_.min_energy; }

std::complex<double> LorentzDrudeIndex::at(double lambda_nm) const {
    check_wavelength_in_range(lambda_nm, min_wavelength_nm(), max_wavelength_nm(), name());
    return index_from_permittivity(lorentz_drude_permittivity(parameters_, spectrum::kPhotonEnergyNm / lambda_nm));
}

}  // namespace surfscatter::material
