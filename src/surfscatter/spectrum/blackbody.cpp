#include "surfscatter/spectrum/blackbody.hpp"

#include "surfscatter/core/error.hpp"

namespace surfscatter::spectrum {

namespace {
constexpr double kSecondRadiationConstant = kPlanckConstant * kSpeedOfLight / kBoltzmannConstant;   // m K
constexpr double kWienDisplacement = kSecondRadiationConstant / 4.965114231744276;                   // m K

double checked_temperature(double temperature_K) {
    require_blackbody_temperature(temperature_K, "blackbody temperature");
    return temperature_K;
}
}  // namespace

void require_blackbody_temperature(double temperature_K, const char* what) {
    if (!(temperature_K > 0 && temperature_K <= kMaxBlackbodyTemperatureK))
        fail("{} must be in (0, {:g}] K, got {}", what, kMaxBlackbodyTemperatureK, temperature_K);
}

Planck::Planck(double temperature_K) : x_times_lambda_(kSecondRadiationConstant * 1e9 / checked_temperature(temperature_K)) {}

double blackbody_radiance(double lambda_nm, double temperature_K) {
    require_positive(lambda_nm, "blackbody wavelength (nm)");
    return Planck(temperature_K)(lambda_nm);
}

double blackbody_peak_wavelength_nm(double temperature_K) {
    require_blackbody_temperature(temperature_K, "blackbody temperature");
    return kWienDisplacement / temperature_K * 1e9;
}

}  // namespace surfscatter::spectrum
