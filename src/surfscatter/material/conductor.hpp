#pragma once
// The metal seen by a BSDF: a refractive index over wavelength, or the perfect conductor (R = 1 everywhere).
#include <complex>
#include <memory>
#include <string>

#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::material {

class Conductor {
public:
    static Conductor perfect();
    explicit Conductor(std::shared_ptr<const RefractiveIndex> ior);

    // "perfect", a built-in metal name, or a .yml/.csv path (see load_refractive_index).
    static Conductor from_name(const std::string& name_or_path);

    bool is_perfect() const { return ior_ == nullptr; }
    // N = n + i k; throws Error for the perfect conductor (it has no finite index).
    std::complex<double> ior(double lambda_nm) const;
    // Unpolarised Fresnel reflectance at incidence cosine cos_theta; 1 for the perfect conductor.
    double reflectance(double cos_theta, double lambda_nm) const {  // inline: BSDF evals of the perfect conductor
        return is_perfect() ? 1.0 : reflectance_sp(cos_theta, lambda_nm).unpolarized();
    }
    FresnelSP reflectance_sp(double cos_theta, double lambda_nm) const;
    std::string name() const;

private:
    std::shared_ptr<const RefractiveIndex> ior_;
};

}  // namespace surfscatter::material
