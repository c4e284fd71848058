#include "surfscatter/surface/height_map_slope.hpp"

#include <cmath>
#include <complex>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/height_map_fft.hpp"

namespace surfscatter::surface {

double rms_slope(const HeightMap& map) {
    const HeightMap flat = remove_tilt(map);
    const double inv_2dx = 0.5 / flat.spacing_x(), inv_2dy = 0.5 / flat.spacing_y();
    double sum = 0.0;
    for (std::size_t iy = 1; iy + 1 < flat.ny(); ++iy)
        for (std::size_t ix = 1; ix + 1 < flat.nx(); ++ix) {
            const double gx = (flat(ix + 1, iy) - flat(ix - 1, iy)) * inv_2dx;
            const double gy = (flat(ix, iy + 1) - flat(ix, iy - 1)) * inv_2dy;
            sum += gx * gx + gy * gy;
        }
    return std::sqrt(sum / static_cast<double>((flat.nx() - 2) * (flat.ny() - 2)));
}

HeightMap gaussian_smooth(const HeightMap& map, double smoothing_um) {
    if (!(std::isfinite(smoothing_um) && smoothing_um > 0.0))
        fail("Gaussian smoothing scale must be a positive number of um, got {}", smoothing_um);
    const HeightMap flat = remove_tilt(map);
    const std::size_t nx = flat.nx(), ny = flat.ny(), ex = 2 * nx, ey = 2 * ny;
    std::vector<double> extended(ex * ey);
    for (std::size_t iy = 0; iy < ey; ++iy)
        for (std::size_t ix = 0; ix < ex; ++ix)
            extended[iy * ex + ix] = flat(ix < nx ? ix : ex - 1 - ix, iy < ny ? iy : ey - 1 - iy);

    auto spectrum = forward_fft_2d(extended, ex, ey);
    const double dzx = 2.0 * kPi / (static_cast<double>(ex) * flat.spacing_x());
    const double dzy = 2.0 * kPi / (static_cast<double>(ey) * flat.spacing_y());
    const std::size_t half = ex / 2 + 1;
    const double norm = 1.0 / static_cast<double>(ex * ey);
    for (std::size_t ky = 0; ky < ey; ++ky) {
        const double zy = static_cast<double>(signed_frequency_index(ky, ey)) * dzy;
        for (std::size_t kx = 0; kx < half; ++kx) {
            const double zx = static_cast<double>(kx) * dzx;
            spectrum[ky * half + kx] *= norm * std::exp(-0.5 * smoothing_um * smoothing_um * (zx * zx + zy * zy));
        }
    }
    const std::vector<double> smoothed_extended = inverse_fft_2d(std::move(spectrum), ex, ey);
    std::vector<double> smoothed(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) smoothed[iy * nx + ix] = smoothed_extended[iy * ex + ix];
    HeightMap result(nx, ny, flat.spacing_x(), flat.spacing_y(), std::move(smoothed));
    result.offset_x = map.offset_x;
    result.offset_y = map.offset_y;
    result.title = map.title;
    return result;
}

double rms_slope_smoothed(const HeightMap& map, double smoothing_um) {
    return rms_slope(gaussian_smooth(map, smoothing_um));
}

}  // namespace surfscatter::surface
