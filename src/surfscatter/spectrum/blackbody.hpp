#pragma once
// Planck's law: spectral radiance of a black body, per unit wavelength.
namespace surfscatter::spectrum {

// Hottest black body accepted (K): Planck's law stays finite (the radiance grows like T in the visible), a billion
// kelvin beyond any lamp or star. Throws Error naming `what` unless 0 < temperature_K <= this.
inline constexpr double kMaxBlackbodyTemperatureK = 1e9;
void require_blackbody_temperature(double temperature_K, const char* what);

// L(lambda, T) in W m^-2 sr^-1 nm^-1 for lambda_nm > 0 and temperature_K > 0 (throws Error otherwise, also on NaN).
// Exact to double round-off (expm1 in the denominator); returns 0 where hc/(lambda k T) > 700, i.e. where the
// radiance is below 1e-280 of its peak.
double blackbody_radiance(double lambda_nm, double temperature_K);

// Wavelength of the maximum of blackbody_radiance (Wien's displacement law), nm.
double blackbody_peak_wavelength_nm(double temperature_K);

}  // namespace surfscatter::spectrum
