#pragma once
// The one range check every RefractiveIndex applies, so the error message is the same for all sources.
#include <string>

namespace surfscatter::material {

// Throws Error "wavelength X nm is outside the range A-B nm of <source>" (also for NaN and lambda <= 0).
void check_wavelength_in_range(double lambda_nm, double min_nm, double max_nm, const std::string& source);

}  // namespace surfscatter::material
