#pragma once
// CODATA 2018 constants (exact since the 2019 SI redefinition), SI units. Source: Tiesinga et al., Rev. Mod. Phys.
// 93, 025010 (2021).
namespace surfscatter::spectrum {

inline constexpr double kPlanckConstant = 6.62607015e-34;    // J s
inline constexpr double kSpeedOfLight = 299792458.0;         // m / s
inline constexpr double kBoltzmannConstant = 1.380649e-23;   // J / K
inline constexpr double kElementaryCharge = 1.602176634e-19; // C
// Photon energy times wavelength, h c / e, in eV nm: E[eV] = kPhotonEnergyNm / lambda[nm].
inline constexpr double kPhotonEnergyNm = kPlanckConstant * kSpeedOfLight / kElementaryCharge * 1e9;

}  // namespace surfscatter::spectrum
