#pragma once
// Evaluates a loaded refractive index across its wavelength range: each value is finite with k >= 0, or an Error
// that names the file (a formula's pole, a range outside the data).
#include <complex>

#include "fuzz_common.hpp"
#include "surfscatter/material/refractive_index.hpp"

namespace surfscatter::fuzz {

inline void check_index(const material::RefractiveIndex& index) {
    const double lo = index.min_wavelength_nm(), hi = index.max_wavelength_nm();
    FUZZ_CHECK(std::isfinite(lo) && std::isfinite(hi) && lo > 0 && lo < hi);
    for (int i = 0; i <= 16; ++i) {
        const double lambda = lo + (hi - lo) * i / 16.0;
        try {
            const std::complex<double> n = index.at(lambda);
            FUZZ_CHECK(std::isfinite(n.real()) && std::isfinite(n.imag()) && n.imag() >= 0);
        } catch (const Error& e) {
            FUZZ_CHECK(std::string(e.what()).find("fuzz.") != std::string::npos);  // names the file
        }
    }
}

}  // namespace surfscatter::fuzz
