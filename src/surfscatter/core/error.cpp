#include "surfscatter/core/error.hpp"

#include <cmath>

namespace surfscatter {

void require_finite(double value, const char* what) {
    if (!std::isfinite(value)) fail("{} must be a finite number, got {}", what, value);
}

void require_positive(double value, const char* what) {
    if (!(value > 0.0) || !std::isfinite(value)) fail("{} must be positive, got {}", what, value);
}

void require_non_negative(double value, const char* what) {
    if (!(value >= 0.0) || !std::isfinite(value)) fail("{} must be >= 0, got {}", what, value);
}

}  // namespace surfscatter
