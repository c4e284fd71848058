#pragma once
// Lorentz-Drude permittivity of metals with the parameters of Rakic, Djurisic, Elazar & Majewski, "Optical
// properties of metallic films for vertical-cavity optoelectronic devices", Appl. Opt. 37(22), 5271 (1998):
//   eps(E) = 1 - f0 wp^2 / (E (E + i g0)) + sum_j f_j wp^2 / ((w_j^2 - E^2) - i E g_j),   E = hc/(e lambda) in eV,
// written with Im(eps) >= 0 so that N = n + i k = sqrt(eps) has k >= 0.
#include <complex>
#include <string>
#include <vector>

#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::material {

struct LorentzOscillator {
    double strength;  // f_j
    double damping;   // g_j, eV
    double energy;    // w_j, eV
};

struct LorentzDrudeParameters {
    std::string name;  // chemical symbol, as in builtin_metal_names()
    double plasma_energy;   // wp, eV
    double drude_strength;  // f0
    double drude_damping;   // g0, eV
    std::vector<LorentzOscillator> oscillators;
    // Photon energies (eV) of the paper's fit, i.e. the range the model is valid in.
    double min_energy, max_energy;
};

// The 11 metals of Rakic et al. 1998 (Table of LD parameters), in builtin_metal_names() order.
const std::vector<LorentzDrudeParameters>& rakic1998_lorentz_drude();

std::complex<double> lorentz_drude_permittivity(const LorentzDrudeParameters& p, double photon_energy_eV);

// N = sqrt(eps), the root with k >= 0 (and n >= 0).
std::complex<double> index_from_permittivity(std::complex<double> permittivity);

class LorentzDrudeIndex final : public RefractiveIndex {
public:
    explicit LorentzDrudeIndex(LorentzDrudeParameters parameters);
    std::complex<double> at(double lambda_nm) const override;
    double min_wavelength_nm() const override;
    double max_wavelength_nm() const override;
    std::string name() const override { return parameters_.name; }
    const LorentzDrudeParameters& parameters() const { return parameters_; }

private:
    LorentzDrudeParameters parameters_;
};

}  // namespace surfscatter::material
