#include "surfscatter/validity/kirchhoff_validity.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/height_map_acv.hpp"

namespace surfscatter::validity {

namespace {

std::vector<double> gaussian_kernel(double sigma_px) {
    const long radius = static_cast<long>(std::ceil(3 * sigma_px));
    std::vector<double> w(static_cast<std::size_t>(2 * radius + 1));
    for (long j = -radius; j <= radius; ++j)
        w[static_cast<std::size_t>(j + radius)] =
            sigma_px > 0 ? std::exp(-0.5 * static_cast<double>(j * j) / (sigma_px * sigma_px)) : 1.0;
    return w;
}

// One separable pass along x (axis 0) or y (axis 1) of value * weight and weight.
void convolve_axis(std::vector<double>& value, std::vector<double>& weight, std::size_t nx, std::size_t ny,
                   const std::vector<double>& kernel, int axis) {
    const long radius = static_cast<long>(kernel.size() / 2);
    std::vector<double> v(value.size(), 0.0), w(weight.size(), 0.0);
    const long n_along = static_cast<long>(axis == 0 ? nx : ny);
    for (std::size_t y = 0; y < ny; ++y)
        for (std::size_t x = 0; x < nx; ++x) {
            const long at = static_cast<long>(axis == 0 ? x : y);
            double sv = 0, sw = 0;
            for (long j = std::max(-radius, -at); j <= std::min(radius, n_along - 1 - at); ++j) {
                const std::size_t src = axis == 0 ? y * nx + static_cast<std::size_t>(at + j)
                                                  : static_cast<std::size_t>(at + j) * nx + x;
                const double k = kernel[static_cast<std::size_t>(j + radius)];
                sv += k * value[src];
                sw += k * weight[src];
            }
            v[y * nx + x] = sv;
            w[y * nx + x] = sw;
        }
    value.swap(v);
    weight.swap(w);
}

double bilinear(const heightmap::HeightMap& map, double fx, double fy, bool& inside) {
    const double last_x = static_cast<double>(map.nx() - 1), last_y = static_cast<double>(map.ny() - 1);
    inside = fx >= 0 && fy >= 0 && fx <= last_x && fy <= last_y;
    if (!inside) return 0;
    // The cell's lower corner, the last pixel's point taken as the far corner of the cell before it.
    const auto ix = static_cast<std::size_t>(std::min(std::floor(fx), last_x - 1));
    const auto iy = static_cast<std::size_t>(std::min(std::floor(fy), last_y - 1));
    inside = map.valid(ix, iy) && map.valid(ix + 1, iy) && map.valid(ix, iy + 1) && map.valid(ix + 1, iy + 1);
    const double tx = fx - static_cast<double>(ix), ty = fy - static_cast<double>(iy);
    return (1 - ty) * ((1 - tx) * map(ix, iy) + tx * map(ix + 1, iy)) +
           ty * ((1 - tx) * map(ix, iy + 1) + tx * map(ix + 1, iy + 1));
}

double median(std::vector<double> v) {
    if (v.empty()) return 0;
    const auto mid = v.begin() + static_cast<long>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

}  // namespace

heightmap::HeightMap smooth_map(const heightmap::HeightMap& map, double sigma_um) {
    require_positive(sigma_um, "smoothing width");
    std::vector<double> value(map.size()), weight(map.size());
    for (std::size_t j = 0; j < map.size(); ++j) {
        weight[j] = map.valid(j) ? 1.0 : 0.0;
        value[j] = weight[j] * map.heights()[j];
    }
    convolve_axis(value, weight, map.nx(), map.ny(), gaussian_kernel(sigma_um / map.spacing_x()), 0);
    convolve_axis(value, weight, map.nx(), map.ny(), gaussian_kernel(sigma_um / map.spacing_y()), 1);
    for (std::size_t j = 0; j < map.size(); ++j) value[j] = map.valid(j) ? value[j] / weight[j] : 0.0;
    return map.with_heights(std::move(value));
}

double shadowed_share(const heightmap::HeightMap& map, double theta_i_deg, double phi_i_deg) {
    if (!(theta_i_deg >= 0 && theta_i_deg < 90)) fail("theta_i must be in [0, 90) degrees, got {}", theta_i_deg);
    require_finite(phi_i_deg, "phi_i");
    if (theta_i_deg == 0) return 0.0;
    double top = -1e300;
    for (std::size_t j = 0; j < map.size(); ++j)
        if (map.valid(j)) top = std::max(top, map.heights()[j]);
    const double step = std::min(map.spacing_x(), map.spacing_y());
    const double rise = step / std::tan(theta_i_deg * kDegree);  // of the ray per step towards the light
    const double sx = step * std::cos(phi_i_deg * kDegree) / map.spacing_x();
    const double sy = step * std::sin(phi_i_deg * kDegree) / map.spacing_y();
    std::size_t valid = 0, shadowed = 0;
    for (std::size_t y = 0; y < map.ny(); ++y)
        for (std::size_t x = 0; x < map.nx(); ++x) {
            if (!map.valid(x, y)) continue;
            ++valid;
            const double h = map(x, y);
            for (double n = 1, ray = h + rise; ray <= top; ++n, ray += rise) {
                bool inside = false;
                const double ground = bilinear(map, static_cast<double>(x) + n * sx, static_cast<double>(y) + n * sy,
                                               inside);
                if (!inside) break;
                if (ground > ray) {
                    ++shadowed;
                    break;
                }
            }
        }
    return static_cast<double>(shadowed) / static_cast<double>(valid);
}

KirchhoffValidity kirchhoff_validity(const heightmap::HeightMap& flat, double lambda_nm, double theta_i_deg,
                                     double phi_i_deg) {
    require_positive(lambda_nm, "wavelength");
    if (!(theta_i_deg >= 0 && theta_i_deg < 90)) fail("theta_i must be in [0, 90) degrees, got {}", theta_i_deg);
    const double lambda_um = lambda_nm * 1e-3;
    const double k = kTwoPi / lambda_um;
    const heightmap::HeightMap map = smooth_map(flat, 1.0 / k);
    KirchhoffValidity v;
    v.k_l = k * surface::acv_measures(flat).correlation_length_um;

    const double cos3 = std::pow(std::cos(theta_i_deg * kDegree), 3);
    const double dx = map.spacing_x(), dy = map.spacing_y();
    std::vector<double> radii;
    std::size_t curved = 0;
    for (std::size_t y = 1; y + 1 < map.ny(); ++y)
        for (std::size_t x = 1; x + 1 < map.nx(); ++x) {
            bool all_valid = true;
            for (std::size_t b = y - 1; b <= y + 1 && all_valid; ++b)
                for (std::size_t a = x - 1; a <= x + 1 && all_valid; ++a) all_valid = map.valid(a, b);
            if (!all_valid) continue;
            const double c = map(x, y);
            const double p = (map(x + 1, y) - map(x - 1, y)) / (2 * dx);
            const double q = (map(x, y + 1) - map(x, y - 1)) / (2 * dy);
            const double r = (map(x + 1, y) - 2 * c + map(x - 1, y)) / (dx * dx);
            const double t = (map(x, y + 1) - 2 * c + map(x, y - 1)) / (dy * dy);
            const double s = (map(x + 1, y + 1) - map(x - 1, y + 1) - map(x + 1, y - 1) + map(x - 1, y - 1)) /
                             (4 * dx * dy);
            const double w2 = 1 + p * p + q * q;
            const double gauss = (r * t - s * s) / (w2 * w2);
            const double mean = ((1 + q * q) * r - 2 * p * q * s + (1 + p * p) * t) / (2 * w2 * std::sqrt(w2));
            const double kappa = std::abs(mean) + std::sqrt(std::max(0.0, mean * mean - gauss));
            const double radius = kappa > 0 ? 1.0 / kappa : 1e300;
            radii.push_back(radius);
            curved += radius * cos3 < lambda_um;
        }
    if (radii.empty()) fail("{}: no valid 3 x 3 neighbourhood to measure the curvature on", flat.origin());
    v.curvature_share = static_cast<double>(curved) / static_cast<double>(radii.size());
    v.median_radius_um = median(std::move(radii));
    v.shadowed_share = shadowed_share(map, theta_i_deg, phi_i_deg);

    std::vector<std::string> failed;
    if (v.k_l < kMinKl) failed.push_back(fmt::format("k l = {:.3g} < {}", v.k_l, kMinKl));
    if (v.curvature_share > kMaxCurvatureShare)
        failed.push_back(fmt::format("{:.3g} % of the map curves with a radius under lambda / cos^3(theta_i)",
                                     100 * v.curvature_share));
    if (v.shadowed_share > kMaxShadowedShare)
        failed.push_back(fmt::format("{:.3g} % of the map is shadowed", 100 * v.shadowed_share));
    v.valid = failed.empty();
    if (v.valid) {
        v.text = fmt::format("Kirchhoff valid (k l = {:.3g}, {:.3g} % curved under lambda, {:.3g} % shadowed)", v.k_l,
                             100 * v.curvature_share, 100 * v.shadowed_share);
    } else {
        v.text = "Kirchhoff outside its validity:";
        for (std::size_t j = 0; j < failed.size(); ++j) v.text += (j ? "; " : " ") + failed[j];
    }
    return v;
}

}  // namespace surfscatter::validity
