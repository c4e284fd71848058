#pragma once
// Planck's law: spectral radiance of a black body, per unit wavelength.
#include <cmath>

#include "surfscatter/math/fast_math.hpp"
#include "surfscatter/spectrum/physical_constants.hpp"

namespace surfscatter::spectrum {

// Hottest black body accepted (K): Planck's law stays finite (the radiance grows like T in the visible), a billion
// kelvin beyond any lamp or star. Throws Error naming `what` unless 0 < temperature_K <= this.
inline constexpr double kMaxBlackbodyTemperatureK = 1e9;
void require_blackbody_temperature(double temperature_K, const char* what);

// Planck's law at one temperature, for inner loops (a renderer's emitters): the temperature is checked once and
// each wavelength costs one inline exponential (math/fast_math.hpp) and no power. L(lambda) in W m^-2 sr^-1 nm^-1
// for lambda_nm > 0 (not checked here). Exact to double round-off: exp(x) - 1 loses at most 1.6 ulp for x >= 1 (and
// fast_exp 2.3e-16), expm1 below; 0 where x = hc/(lambda k T) > 700, i.e. where the radiance is below 1e-280 of its
// peak.
class Planck {
public:
    explicit Planck(double temperature_K);  // require_blackbody_temperature
    double operator()(double lambda_nm) const {
        const double x = x_times_lambda_ / lambda_nm;
        if (x > 700.0) return 0.0;  // exp(x) overflows
        const double l2 = lambda_nm * lambda_nm;
        return kFirstConstantNm / (l2 * l2 * lambda_nm * (x < 1.0 ? std::expm1(x) : math::fast_exp(x) - 1.0));
    }

private:
    // 2 h c^2 (W m^2 sr^-1) for lambda in nm and radiance per nm: x 1e45 (lambda^5 in nm^5) x 1e-9 (per m -> per nm).
    static constexpr double kFirstConstantNm = 2.0 * kPlanckConstant * kSpeedOfLight * kSpeedOfLight * 1e36;
    double x_times_lambda_;  // h c / (k T) in nm
};

// L(lambda, T) in W m^-2 sr^-1 nm^-1 for lambda_nm > 0 and temperature_K as require_blackbody_temperature (throws
// Error otherwise, also on NaN), as Planck.
double blackbody_radiance(double lambda_nm, double temperature_K);

// Wavelength of the maximum of blackbody_radiance (Wien's displacement law), nm.
double blackbody_peak_wavelength_nm(double temperature_K);

}  // namespace surfscatter::spectrum
