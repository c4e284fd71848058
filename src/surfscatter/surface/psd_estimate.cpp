#include "surfscatter/surface/psd_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <complex>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::surface {

double Psd2d::zeta_x(std::size_t kx) const { return static_cast<double>(kx) * dzeta_x; }

double Psd2d::zeta_y(std::size_t ky) const { return static_cast<double>(heightmap::signed_frequency_index(ky, ny)) * dzeta_y; }

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

std::vector<double> window_table(Window window, std::size_t n) {
    std::vector<double> w(n);
    for (std::size_t i = 0; i < n; ++i) w[i] = window_value(window, i, n);
    return w;
}

// The (form-removed) map multiplied by the window, with invalid points 0, and sum w^2, sum (w m)^2.
struct WindowedMap {
    std::vector<double> wx, wy, values;
    double window_power = 0.0, valid_power = 0.0;
};

WindowedMap windowed(const heightmap::HeightMap& flat, Window window) {
    WindowedMap out;
    out.wx = window_table(window, flat.nx());
    out.wy = window_table(window, flat.ny());
    out.values.resize(flat.size());
    for (std::size_t iy = 0; iy < flat.ny(); ++iy)
        for (std::size_t ix = 0; ix < flat.nx(); ++ix) {
            const double w = out.wx[ix] * out.wy[iy];
            out.window_power += w * w;
            if (!flat.valid(ix, iy)) continue;
            out.values[iy * flat.nx() + ix] = w * flat(ix, iy);
            out.valid_power += w * w;
        }
    return out;
}

Psd2d empty_psd(const heightmap::HeightMap& map, Window window) {
    Psd2d psd;
    psd.window = window;
    psd.nx = map.nx();
    psd.ny = map.ny();
    psd.dzeta_x = 2.0 * kPi / map.width();
    psd.dzeta_y = 2.0 * kPi / map.height();
    return psd;
}

// sum_i w(i) w(i + t) for t = -(n-1) .. n-1, at index t mod 2n.
std::vector<double> window_autocorrelation(const std::vector<double>& w) {
    const std::size_t n = w.size();
    std::vector<double> a(2 * n, 0.0);
    for (std::size_t t = 0; t < n; ++t) {
        double sum = 0.0;
        for (std::size_t i = 0; i + t < n; ++i) sum += w[i] * w[i + t];
        a[t] = sum;
        if (t > 0) a[2 * n - t] = sum;
    }
    return a;
}

Psd2d periodogram(const heightmap::HeightMap& flat, Window window) {
    const WindowedMap weighted = windowed(flat, window);
    const auto spectrum = heightmap::forward_fft_2d(weighted.values, flat.nx(), flat.ny());
    Psd2d psd = empty_psd(flat, window);
    const double scale = flat.spacing_x() * flat.spacing_y() / (4.0 * kPi * kPi * weighted.window_power);
    psd.values.resize(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) psd.values[i] = std::norm(spectrum[i]) * scale;
    return psd;
}

}  // namespace

namespace {

// DFT (real part, half plane) of C^(t) L(t): the window-weighted mean lag product of `field` over the pairs of
// points whose weights `weights` (w m: window times validity) are both non-zero, times the window's own
// autocorrelation L(t), folded modulo (nx, ny) so that one nx x ny DFT gives it at the map's frequencies.
std::vector<double> masked_correlogram(const std::vector<double>& field, const std::vector<double>& weights,
                                       const WindowedMap& window, std::size_t nx, std::size_t ny) {
    const std::size_t ex = 2 * nx, ey = 2 * ny;
    std::vector<double> weighted(field.size());
    for (std::size_t i = 0; i < field.size(); ++i) weighted[i] = weights[i] * field[i];
    const std::vector<double> products = heightmap::linear_autocorrelation(weighted, nx, ny);  // sum (wmg)(wmg)
    const std::vector<double> pairs = heightmap::linear_autocorrelation(weights, nx, ny);      // sum (wm)(wm)
    const std::vector<double> lx = window_autocorrelation(window.wx), ly = window_autocorrelation(window.wy);
    // Lags with pair weight below 1e-12 of the zero lag's (no valid pair; FFT rounding is ~1e-16) contribute 0.
    const double min_pairs = 1e-12 * pairs[0];
    std::vector<double> folded(nx * ny, 0.0);
    for (std::size_t ty = 0; ty < ey; ++ty) {
        if (ty == ny) continue;  // lag +-ny: outside the map
        for (std::size_t tx = 0; tx < ex; ++tx) {
            if (tx == nx) continue;
            const std::size_t lag = ty * ex + tx;
            if (!(pairs[lag] > min_pairs)) continue;
            folded[(ty % ny) * nx + tx % nx] += products[lag] / pairs[lag] * lx[tx] * ly[ty] / window.window_power;
        }
    }
    const auto spectrum = heightmap::forward_fft_2d(folded, nx, ny);
    std::vector<double> real(spectrum.size());
    for (std::size_t i = 0; i < spectrum.size(); ++i) real[i] = spectrum[i].real();
    return real;
}

}  // namespace

Psd2d masked_periodogram(const heightmap::HeightMap& flat, Window window) {
    const std::size_t nx = flat.nx(), ny = flat.ny();
    const WindowedMap weighted = windowed(flat, window);
    Psd2d psd = empty_psd(flat, window);
    psd.valid_weight = weighted.valid_power / weighted.window_power;
    const double scale = flat.spacing_x() * flat.spacing_y() / (4.0 * kPi * kPi);

    // Heights (rings <= kMaskedDirectRings): w m, the heights with invalid points 0.
    std::vector<double> heights(flat.size(), 0.0), weights(flat.size(), 0.0);
    // Slopes between valid neighbours (every other ring), with the same window.
    std::vector<double> gx(flat.size(), 0.0), gy(flat.size(), 0.0), qx(flat.size(), 0.0), qy(flat.size(), 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            if (!flat.valid(ix, iy)) continue;
            const std::size_t i = iy * nx + ix;
            const double w = weighted.wx[ix] * weighted.wy[iy];
            heights[i] = flat(ix, iy);
            weights[i] = w;
            if (ix + 1 < nx && flat.valid(ix + 1, iy)) {
                gx[i] = (flat(ix + 1, iy) - flat(ix, iy)) / flat.spacing_x();
                qx[i] = w;
            }
            if (iy + 1 < ny && flat.valid(ix, iy + 1)) {
                gy[i] = (flat(ix, iy + 1) - flat(ix, iy)) / flat.spacing_y();
                qy[i] = w;
            }
        }
    const std::vector<double> direct = masked_correlogram(heights, weights, weighted, nx, ny);
    const std::vector<double> sx = masked_correlogram(gx, qx, weighted, nx, ny);
    const std::vector<double> sy = masked_correlogram(gy, qy, weighted, nx, ny);
    const std::vector<double> lx = window_autocorrelation(weighted.wx), ly = window_autocorrelation(weighted.wy);
    const double rho_x = (lx[1] + lx[nx + 1]) / lx[0], rho_y = (ly[1] + ly[ny + 1]) / ly[0];
    const double dx2 = flat.spacing_x() * flat.spacing_x(), dy2 = flat.spacing_y() * flat.spacing_y();
    const double ring_width = std::max(psd.dzeta_x, psd.dzeta_y);
    psd.values.resize(direct.size());
    for (std::size_t ky = 0; ky < ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const std::size_t k = ky * psd.half_nx() + kx;
            const double ring = std::hypot(psd.zeta_x(kx), psd.zeta_y(ky)) / ring_width;
            if (ring < kMaskedDirectRings + 0.5) {
                psd.values[k] = direct[k] * scale;
                continue;
            }
            const double transfer = (2.0 - 2.0 * rho_x * std::cos(psd.zeta_x(kx) * flat.spacing_x())) / dx2 +
                                    (2.0 - 2.0 * rho_y * std::cos(psd.zeta_y(ky) * flat.spacing_y())) / dy2;
            psd.values[k] = (sx[k] + sy[k]) / transfer * scale;
        }
    return psd;
}

double windowed_variance(const heightmap::HeightMap& map, Window window, heightmap::Form form) {
    const WindowedMap weighted = windowed(heightmap::remove_form(map, form), window);
    double sum = 0.0;
    for (double v : weighted.values) sum += v * v;
    return sum / weighted.valid_power;
}

Psd2d estimate_psd(const heightmap::HeightMap& map, Window window, heightmap::Form form) {
    const heightmap::HeightMap flat = heightmap::remove_form(map, form);
    return flat.has_invalid() ? masked_periodogram(flat, window) : periodogram(flat, window);
}

RadialPsd radial_average(const Psd2d& psd) {
    RadialPsd radial;
    radial.window = psd.window;
    radial.valid_weight = psd.valid_weight;
    radial.dzeta = std::max(psd.dzeta_x, psd.dzeta_y);
    const double nyquist = std::min(psd.dzeta_x * static_cast<double>(psd.nx / 2),
                                    psd.dzeta_y * static_cast<double>(psd.ny / 2));
    // Rings up to Nyquist, ring 0 included; a grid far finer along one axis than the other may have ring 0 only.
    const double ring_count = std::floor(nyquist / radial.dzeta - 0.5) + 1;
    const std::size_t rings = ring_count >= 1 ? static_cast<std::size_t>(ring_count) : 1;
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

double effective_samples(Window window, double count, double valid_weight) {
    const double correlation = window == Window::hann ? 35.0 / 18.0 : 1.0;
    return count * valid_weight / (2.0 * correlation);
}

double rms_slope_from_psd(const Psd2d& psd) {
    double sum = 0.0;
    for (std::size_t ky = 0; ky < psd.ny; ++ky)
        for (std::size_t kx = 0; kx < psd.half_nx(); ++kx) {
            const double zx = psd.zeta_x(kx), zy = psd.zeta_y(ky);
            sum += psd.multiplicity(kx) * (zx * zx + zy * zy) * psd.values[ky * psd.half_nx() + kx];
        }
    if (!(sum > 0.0))
        fail("rms slope from the PSD: the masked PSD estimate sums to {} (too few valid pairs of points)", sum);
    return std::sqrt(sum * psd.dzeta_x * psd.dzeta_y);
}

}  // namespace surfscatter::surface
