#include "surfscatter/surface/height_map.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::surface {

void require_valid_spacing(double spacing_um, const std::string& what) {
    if (!(spacing_um >= kMinSpacingUm && spacing_um <= kMaxSpacingUm))
        fail("{} must be between {} and {} um, got {}", what, kMinSpacingUm, kMaxSpacingUm, spacing_um);
}

HeightMap::HeightMap(std::size_t nx, std::size_t ny, double spacing_x_um, double spacing_y_um,
                     std::vector<double> heights_um, const std::string& origin)
    : nx_(nx), ny_(ny), spacing_x_(spacing_x_um), spacing_y_(spacing_y_um), heights_(std::move(heights_um)) {
    if (nx < kMinHeightMapSize || ny < kMinHeightMapSize)
        fail("{}: grid is {} x {} samples; at least {} x {} are needed", origin, nx, ny, kMinHeightMapSize,
             kMinHeightMapSize);
    require_valid_spacing(spacing_x_um, origin + ": x pixel spacing");
    require_valid_spacing(spacing_y_um, origin + ": y pixel spacing");
    if (heights_.size() != nx * ny)
        fail("{}: {} heights given for a {} x {} grid", origin, heights_.size(), nx, ny);
    for (std::size_t i = 0; i < heights_.size(); ++i)
        if (!std::isfinite(heights_[i]))
            fail("{}: height at column {}, row {} is {} (every height must be finite)", origin, i % nx, i / nx,
                 heights_[i]);
}

Plane fit_plane(const HeightMap& map) {
    const std::size_t nx = map.nx(), ny = map.ny();
    const double xc = 0.5 * static_cast<double>(nx - 1), yc = 0.5 * static_cast<double>(ny - 1);
    double sum = 0.0, sum_x = 0.0, sum_y = 0.0;
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double h = map(ix, iy);
            sum += h;
            sum_x += h * (static_cast<double>(ix) - xc);
            sum_y += h * (static_cast<double>(iy) - yc);
        }
    // sum over the grid of (i - c)^2 = n (n^2 - 1) / 12 per axis, times the other axis' count.
    const double dnx = static_cast<double>(nx), dny = static_cast<double>(ny);
    const double xx = dny * dnx * (dnx * dnx - 1.0) / 12.0;
    const double yy = dnx * dny * (dny * dny - 1.0) / 12.0;
    Plane plane;
    plane.mean = sum / (dnx * dny);
    plane.slope_x = sum_x / xx / map.spacing_x();
    plane.slope_y = sum_y / yy / map.spacing_y();
    return plane;
}

HeightMap remove_tilt(const HeightMap& map) {
    const Plane plane = fit_plane(map);
    const std::size_t nx = map.nx(), ny = map.ny();
    const double xc = 0.5 * static_cast<double>(nx - 1), yc = 0.5 * static_cast<double>(ny - 1);
    std::vector<double> residual(map.size());
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            residual[iy * nx + ix] = map(ix, iy) - plane.mean -
                                     plane.slope_x * (static_cast<double>(ix) - xc) * map.spacing_x() -
                                     plane.slope_y * (static_cast<double>(iy) - yc) * map.spacing_y();
    HeightMap result(nx, ny, map.spacing_x(), map.spacing_y(), std::move(residual));
    result.offset_x = map.offset_x;
    result.offset_y = map.offset_y;
    result.title = map.title;
    return result;
}

double rms_height(const HeightMap& map) {
    const HeightMap flat = remove_tilt(map);
    double sum = 0.0;
    for (double h : flat.heights()) sum += h * h;
    return std::sqrt(sum / static_cast<double>(flat.size()));
}

}  // namespace surfscatter::surface
