#include "surfscatter/spectrum/blackbody.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/physical_constants.hpp"

namespace surfscatter::spectrum {

namespace {
constexpr double kFirstRadiationConstantL = 2.0 * kPlanckConstant * kSpeedOfLight * kSpeedOfLight;  // W m^2 sr^-1
constexpr double kSecondRadiationConstant = kPlanckConstant * kSpeedOfLight / kBoltzmannConstant;   // m K
constexpr double kWienDisplacement = kSecondRadiationConstant / 4.965114231744276;                   // m K
}  // namespace

void require_blackbody_temperature(double temperature_K, const char* what) {
    if (!(temperature_K > 0 && temperature_K <= kMaxBlackbodyTemperatureK))
        fail("{} must be in (0, {:g}] K, got {}", what, kMaxBlackbodyTemperatureK, temperature_K);
}

double blackbody_radiance(double lambda_nm, double temperature_K) {
    require_positive(lambda_nm, "blackbody wavelength (nm)");
    require_blackbody_temperature(temperature_K, "blackbody temperature");
    const double lambda_m = lambda_nm * 1e-9;
    const double x = kSecondRadiationConstant / (lambda_m * temperature_K);
    if (x > 700.0) return 0.0;  // exp(x) overflows; the radiance is below 1e-280 of its peak
    const double per_metre = kFirstRadiationConstantL / (std::pow(lambda_m, 5) * std::expm1(x));
    return per_metre * 1e-9;
}

double blackbody_peak_wavelength_nm(double temperature_K) {
    require_blackbody_temperature(temperature_K, "blackbody temperature");
    return kWienDisplacement / temperature_K * 1e9;
}

}  // namespace surfscatter::spectrum
