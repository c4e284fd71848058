#pragma once
// Complex refractive index N = n + i k (k >= 0) of a metal as a function of wavelength (nm).
// Sources: built-in Lorentz-Drude models (Rakic et al. 1998), refractiveindex.info YAML files, CSV tables.
#include <complex>
#include <memory>
#include <string>
#include <vector>

namespace surfscatter::material {

class RefractiveIndex {
public:
    virtual ~RefractiveIndex() = default;
    // N = n + i k at lambda_nm; throws Error naming the wavelength and the valid range outside it.
    virtual std::complex<double> at(double lambda_nm) const = 0;
    virtual double min_wavelength_nm() const = 0;
    virtual double max_wavelength_nm() const = 0;
    virtual std::string name() const = 0;
};

// Names of the built-in metals (Ag, Al, Au, Be, Cr, Cu, Ni, Pd, Pt, Ti, W).
std::vector<std::string> builtin_metal_names();

// A built-in metal by name (case-sensitive as in builtin_metal_names()), or a path to a refractiveindex.info
// .yml file or a `wavelength_nm,n,k` .csv file. Throws Error naming the value if it is neither.
std::shared_ptr<const RefractiveIndex> load_refractive_index(const std::string& name_or_path);

}  // namespace surfscatter::material
