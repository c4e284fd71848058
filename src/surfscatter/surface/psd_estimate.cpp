#include "surfscatter/surface/psd_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/height_map_fft.hpp"

namespace surfscatter::surface {

double Psd2d::zeta_x(std::size_t kx) const { return static_cast<double>(kx) * dzeta_x; }

double Psd2d::zeta_y(std::size_t ky) const { return static_cast<double>(signed_frequency_index(ky, ny)) * dzeta_y; }

double Psd2d::multiplicity(std::size_t kx) const {
    // Columns 0 and (for even nx) nx/2 are their own Hermitian mirror; every other column also stands for -kx.
    return (kx == 0 || (nx % 2 == 0 && kx == nx / 2)) ? 1.0 : 2.0;
}

double Psd2d::integral() const {
    double sum = 0.0;
    for (std::size_t ky = 0; ky < ny; ++ky)
        for (std::size_t kx = 0; kx < half_nx(); ++kx) sum += multiplicity(kx) * values[ky * half_nx() + kx];
    return sum * dzeta_x * dzeta_y;
}

double window_value(Window window, std::size_t i, std::size_t n) {
    if (window == Window::rectangular) return 1.0;
    const double s = std::sin(kPi * (static_cast<double>(i) + 0.5) / static_cast<double>(n));
    return s * s;
}

namespace {
// The tilt-removed map multiplied by the window, and sum w^2.
std::vector<double> windowed_heights(const HeightMap& map, Window window, double& window_power) {
    const HeightMap flat = remove_tilt(map);
    std::vector<double> wx(map.nx()), wy(map.ny());
    for (std::size_t i = 0; i < map.nx(); ++i) wx[i] = window_value(window, i, map.nx());
    for (std::size_t i = 0; i < map.ny(); ++i) wy[i] = window_value(window, i, map.ny());
    std::vector<double> out(map.size());
    window_power = 0.0;
    for (std::size_t iy = 0; iy < map.ny(); ++iy)
        for (std::size_t ix = 0; ix < map.nx(); ++ix) {
            const double w = wx[ix] * wy[iy];
            out[iy * map.nx() + ix] = w * flat(ix, iy);
            window_power += w * w;
        }
    return out;
}
}  // namespace

double windowed_variance(const HeightMap& map, Window window) {
    double window_power = 0.0;
    const std::vector<double> weighted = windowed_heights(map, window, window_power);
    double sum = 0.0;
    for (double v : weighted) sum += v * v;
    return sum / window_power;
}

Psd2d estimate_psd(const HeightMap& map, Window window) {
    double window_power = 0.0;
    const std::vector<double> weighted = windowed_heights(map, window, window_power);
    const auto spectrum = forward_fft_2d(weighted, map.nx(), map.ny());
    Psd2d psd;
    psd.window = window;
    psd.nx = map.nx();
    psd.ny = map.ny();
    psd.dzeta_x = 2.0 * kPi / map.width();
    psd.dzeta_y = 2.0 * kPi / map.height();
    const double scale = map.spacing_x() * map.spacing_y() / (4.0 * kPi * kPi * window_power);
    psd.values.resize(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) psd.values[i] = std::norm(spectrum[i]) * scale;
    return psd;
}

RadialPsd radial_average(const Psd2d& psd) {
    RadialPsd radial;
    radial.window = psd.window;
    radial.dzeta = std::max(psd.dzeta_x, psd.dzeta_y);
    const double nyquist = std::min(psd.dzeta_x * static_cast<double>(psd.nx / 2),
                                    psd.dzeta_y * static_cast<double>(psd.ny / 2));
    const auto rings = static_cast<std::size_t>(std::floor(nyquist / radial.dzeta - 0.5)) + 1;  // incl. ring 0
    std::vector<double> sum_zeta(rings, 0.0), sum_psd(rings, 0.0), count(rings, 0.0);
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zeta = std::hypot(psd.zeta_x(kx), psd.zeta_y(ky));
            const auto ring = static_cast<std::size_t>(std::floor(zeta / radial.dzeta + 0.5));
            if (ring >= rings) continue;
            const double m = psd.multiplicity(kx);
            sum_zeta[ring] += m * zeta;
            sum_psd[ring] += m * psd.values[ky * psd.half_nx() + kx];
            count[ring] += m;
        }
    for (std::size_t ring = 1; ring < rings; ++ring) {
        if (count[ring] == 0.0) continue;
        radial.zeta.push_back(sum_zeta[ring] / count[ring]);
        radial.psd.push_back(sum_psd[ring] / count[ring]);
        radial.count.push_back(count[ring]);
    }
    return radial;
}

double effective_samples(Window window, double count) {
    const double correlation = window == Window::hann ? 35.0 / 18.0 : 1.0;
    return count / (2.0 * correlation);
}

double rms_slope_from_psd(const Psd2d& psd) {
    double sum = 0.0;
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zx = psd.zeta_x(kx), zy = psd.zeta_y(ky);
            sum += psd.multiplicity(kx) * (zx * zx + zy * zy) * psd.values[ky * psd.half_nx() + kx];
        }
    return std::sqrt(sum * psd.dzeta_x * psd.dzeta_y);
}

}  // namespace surfscatter::surface
