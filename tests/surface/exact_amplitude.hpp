#pragma once
// Periodic test maps synthesised with exact spectral amplitudes and random phases, so that each map's own
// periodogram is known exactly, and the self-convolutions of eq. 2 on the map's own lattice: the independent
// reference of the measured route (tests/surface/test_map_statistics.cpp, tests/bsdf/test_measured_reference.cpp).
#include <cmath>
#include <complex>
#include <random>
#include <utility>
#include <vector>

#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface::test {

// A periodic map whose periodogram |H_k|^2 dx dy / (4 pi^2 N) equals P(|zeta_k|) at every lattice point but DC.
inline heightmap::HeightMap exact_amplitude_map(const RadialStatistics& stats, std::size_t n, double dx, unsigned seed, double scale = 1.0) {
    const std::size_t half = n / 2 + 1;
    std::vector<std::complex<double>> spectrum(n * half);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * kPi);
    const double dzeta = 2.0 * kPi / (static_cast<double>(n) * dx);
    const double norm = 4.0 * kPi * kPi * static_cast<double>(n * n) / (dx * dx);
    for (std::size_t ky = 0; ky < n; ++ky)
        for (std::size_t kx = 0; kx < half; ++kx) {
            const double zx = static_cast<double>(kx) * dzeta;
            const double zy = static_cast<double>(heightmap::signed_frequency_index(ky, n)) * dzeta;
            const double amplitude = std::sqrt(norm * stats.psd(std::hypot(zx, zy)));
            spectrum[ky * half + kx] = std::polar(amplitude, phase(rng));
        }
    // Columns kx = 0 and n/2 hold their own mirrors: make them Hermitian, their self-mirrored entries real.
    for (std::size_t kx : {std::size_t{0}, n / 2})
        for (std::size_t ky = 0; ky < n; ++ky) {
            const std::size_t mirror = (n - ky) % n;
            if (mirror == ky) spectrum[ky * half + kx] = std::abs(spectrum[ky * half + kx]);
            else if (mirror < ky) spectrum[ky * half + kx] = std::conj(spectrum[mirror * half + kx]);
        }
    spectrum[0] = 0.0;
    std::vector<double> h = heightmap::inverse_fft_2d(std::move(spectrum), n, n);
    for (double& v : h) v *= scale / static_cast<double>(n * n);
    return heightmap::HeightMap(n, n, dx, dx, std::move(h), "exact-amplitude map");
}

// Circular normalised ACV of a zero-mean periodic map, lags wrapped into [-n/2, n/2).
inline std::vector<double> circular_rho(const heightmap::HeightMap& map) {
    const std::size_t n = map.nx();
    double c0 = 0.0;
    for (double v : map.heights()) c0 += v * v;
    c0 /= static_cast<double>(map.size());
    auto spectrum = heightmap::forward_fft_2d(map.heights(), n, n);
    for (auto& c : spectrum) c = std::norm(c);
    std::vector<double> rho = heightmap::inverse_fft_2d(std::move(spectrum), n, n);
    for (double& v : rho) v /= static_cast<double>(n * n) * static_cast<double>(n * n) * c0;
    return rho;
}

// Ring means of P-hat^{*m} on the map's own lattice: (dx dy / 4 pi^2) DFT[rho^m] (eq. 2 on the lattice, the m-fold
// discrete self-convolution of the normalised periodogram), averaged over the lattice points of each ring of width
// dzeta; returns {mean |zeta|, mean value} per ring 1 .. n/2 - 1.
inline std::vector<std::pair<double, double>> lattice_rings(const std::vector<double>& rho, std::size_t n, double dx, int m) {
    std::vector<double> power(rho.size());
    for (std::size_t i = 0; i < rho.size(); ++i) power[i] = std::pow(rho[i], m);
    const auto spectrum = heightmap::forward_fft_2d(power, n, n);
    const std::size_t half = n / 2 + 1;
    const double dzeta = 2.0 * kPi / (static_cast<double>(n) * dx);
    std::vector<double> sum_z(n / 2, 0.0), sum_v(n / 2, 0.0), count(n / 2, 0.0);
    for (std::size_t ky = 0; ky < n; ++ky)
        for (std::size_t kx = 0; kx < half; ++kx) {
            const double zx = static_cast<double>(kx) * dzeta;
            const double zy = static_cast<double>(heightmap::signed_frequency_index(ky, n)) * dzeta;
            const double z = std::hypot(zx, zy);
            const std::size_t ring = static_cast<std::size_t>(std::lround(z / dzeta));
            if (ring == 0 || ring >= n / 2) continue;
            const double weight = (kx == 0 || kx == n / 2) ? 1.0 : 2.0;  // half-plane entries stand for two
            sum_z[ring] += weight * z;
            sum_v[ring] += weight * spectrum[ky * half + kx].real() * dx * dx / (4.0 * kPi * kPi);
            count[ring] += weight;
        }
    std::vector<std::pair<double, double>> rings;
    for (std::size_t r = 1; r < n / 2; ++r) rings.emplace_back(sum_z[r] / count[r], sum_v[r] / count[r]);
    return rings;
}

// P-hat^{*m} at zeta = 0 on the lattice: (dx dy / 4 pi^2) sum_t rho(t)^m (0 for m = 1: the mean is removed).
inline double lattice_dc(const std::vector<double>& rho, double dx, int m) {
    double sum = 0.0;
    for (double v : rho) sum += std::pow(v, m);
    return sum * dx * dx / (4.0 * kPi * kPi);
}

}  // namespace surfscatter::surface::test
