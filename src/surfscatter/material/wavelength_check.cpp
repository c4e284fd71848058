#include "surfscatter/material/wavelength_check.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::material {

void check_wavelength_in_range(double lambda_nm, double min_nm, double max_nm, const std::string& source) {
    if (!(lambda_nm > 0) || !std::isfinite(lambda_nm)) fail("wavelength must be a positive number of nm, got {}", lambda_nm);
    // Relative slack so that the table's own end points, after a round trip through micrometres, are inside.
    const double slack = 1e-9 * max_nm;
    if (lambda_nm < min_nm - slack || lambda_nm > max_nm + slack)
        fail("wavelength {} nm is outside the range {:.6g}-{:.6g} nm of {}", lambda_nm, min_nm, max_nm, source);
}

}  // namespace surfscatter::material
