#include "surfscatter/surface/height_map_slope.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::surface {

namespace {

// f(gx, gy) for the central-difference gradient at every interior point of `flat` whose four neighbours are valid;
// the number of such points. Error if there is none.
template <typename F>
std::size_t for_each_gradient(const heightmap::HeightMap& flat, const std::string& origin, F&& f) {
    const double inv_2dx = 0.5 / flat.spacing_x(), inv_2dy = 0.5 / flat.spacing_y();
    std::size_t count = 0;
    for (std::size_t iy = 1; iy + 1 < flat.ny(); ++iy)
        for (std::size_t ix = 1; ix + 1 < flat.nx(); ++ix) {
            if (!(flat.valid(ix - 1, iy) && flat.valid(ix + 1, iy) && flat.valid(ix, iy - 1) &&
                  flat.valid(ix, iy + 1)))
                continue;
            f((flat(ix + 1, iy) - flat(ix - 1, iy)) * inv_2dx, (flat(ix, iy + 1) - flat(ix, iy - 1)) * inv_2dy);
            ++count;
        }
    if (count == 0) fail("{}: no point has four valid neighbours; the slope is undefined", origin);
    return count;
}

}  // namespace

double rms_slope(const heightmap::HeightMap& map, heightmap::Form form) {
    double sum = 0.0;
    const std::size_t count =
        for_each_gradient(heightmap::remove_form(map, form), map.origin(), [&](double gx, double gy) { sum += gx * gx + gy * gy; });
    return std::sqrt(sum / static_cast<double>(count));
}

Vec2 slope_variances_lay(const heightmap::HeightMap& map, double lay_angle_rad, heightmap::Form form) {
    const double c = std::cos(lay_angle_rad), s = std::sin(lay_angle_rad);
    double sum_u = 0.0, sum_v = 0.0;
    const std::size_t count = for_each_gradient(heightmap::remove_form(map, form), map.origin(), [&](double gx, double gy) {
        const double gu = c * gx + s * gy, gv = -s * gx + c * gy;
        sum_u += gu * gu;
        sum_v += gv * gv;
    });
    return {sum_u / static_cast<double>(count), sum_v / static_cast<double>(count)};
}

SlopeCovariance slope_covariance(const heightmap::HeightMap& map, heightmap::Form form) {
    const heightmap::HeightMap flat = heightmap::remove_form(map, form);
    SlopeCovariance c;
    const std::size_t count = for_each_gradient(flat, map.origin(), [&](double gx, double gy) {
        c.xx += gx * gx;
        c.yy += gy * gy;
        c.xy += gx * gy;
    });
    const double n = static_cast<double>(count);
    c.xx /= n;
    c.yy /= n;
    c.xy /= n;
    return c;
}

SlopeCovariance::Axes SlopeCovariance::axes() const {
    // Eigenvalues of [[xx, xy], [xy, yy]]; the larger one's eigenvector at 0.5 atan2(2 xy, xx - yy) from x.
    const double mean = 0.5 * (xx + yy), half = 0.5 * (xx - yy), r = std::hypot(half, xy);
    const double major = 0.5 * std::atan2(2.0 * xy, xx - yy);
    return {std::max(0.0, mean - r), mean + r, major + 0.5 * kPi};
}

namespace {

// G * v by FFT of the 2nx x 2ny mirror extension of v (nx x ny row-major).
std::vector<double> mirrored_gaussian_convolution(const std::vector<double>& v, std::size_t nx, std::size_t ny,
                                                  double dx, double dy, double smoothing_um) {
    const std::size_t ex = 2 * nx, ey = 2 * ny;
    std::vector<double> extended(ex * ey);
    for (std::size_t iy = 0; iy < ey; ++iy)
        for (std::size_t ix = 0; ix < ex; ++ix)
            extended[iy * ex + ix] = v[(iy < ny ? iy : ey - 1 - iy) * nx + (ix < nx ? ix : ex - 1 - ix)];

    auto spectrum = heightmap::forward_fft_2d(extended, ex, ey);
    const double dzx = 2.0 * kPi / (static_cast<double>(ex) * dx);
    const double dzy = 2.0 * kPi / (static_cast<double>(ey) * dy);
    const std::size_t half = ex / 2 + 1;
    const double norm = 1.0 / static_cast<double>(ex * ey);
    for (std::size_t ky = 0; ky < ey; ++ky) {
        const double zy = static_cast<double>(heightmap::signed_frequency_index(ky, ey)) * dzy;
        for (std::size_t kx = 0; kx < half; ++kx) {
            const double zx = static_cast<double>(kx) * dzx;
            spectrum[ky * half + kx] *= norm * std::exp(-0.5 * smoothing_um * smoothing_um * (zx * zx + zy * zy));
        }
    }
    const std::vector<double> smoothed_extended = heightmap::inverse_fft_2d(std::move(spectrum), ex, ey);
    std::vector<double> smoothed(nx * ny);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) smoothed[iy * nx + ix] = smoothed_extended[iy * ex + ix];
    return smoothed;
}

}  // namespace

heightmap::HeightMap gaussian_smooth(const heightmap::HeightMap& map, double smoothing_um, heightmap::Form form) {
    if (!(std::isfinite(smoothing_um) && smoothing_um > 0.0))
        fail("Gaussian smoothing scale must be a positive number of um, got {}", smoothing_um);
    const heightmap::HeightMap flat = heightmap::remove_form(map, form);
    const std::size_t nx = flat.nx(), ny = flat.ny();
    std::vector<double> smoothed = mirrored_gaussian_convolution(flat.heights(), nx, ny, flat.spacing_x(),
                                                                 flat.spacing_y(), smoothing_um);
    if (flat.has_invalid()) {
        std::vector<double> mask(flat.size());
        for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = flat.valid(i) ? 1.0 : 0.0;
        const std::vector<double> weight =
            mirrored_gaussian_convolution(mask, nx, ny, flat.spacing_x(), flat.spacing_y(), smoothing_um);
        // A valid point's own Gaussian weight is at least that of its pixel, so the weight is positive there.
        for (std::size_t i = 0; i < smoothed.size(); ++i) smoothed[i] = flat.valid(i) ? smoothed[i] / weight[i] : 0.0;
    }
    return flat.with_heights(std::move(smoothed));
}

void require_smoothing(double smoothing_um, const heightmap::HeightMap& map, const char* what) {
    require_positive(smoothing_um, what);
    if (smoothing_um > std::max(map.width(), map.height()))
        fail("{} {} um is wider than the {:g} x {:g} um map (the smoothed map would be flat)", what, smoothing_um,
             map.width(), map.height());
}

double rms_slope_smoothed(const heightmap::HeightMap& map, double smoothing_um, heightmap::Form form) {
    return rms_slope(gaussian_smooth(map, smoothing_um, form), heightmap::Form::none);
}

}  // namespace surfscatter::surface
