#include "surfscatter/surface/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <random>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::surface {

namespace {
// n standard normal deviates from mt19937_64 by the Box-Muller transform (two per pair of uniforms).
std::vector<double> white_noise(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 engine(seed);
    auto uniform_open = [&engine] {  // in (0, 1): 53 random bits, centred in their cell
        return (static_cast<double>(engine() >> 11) + 0.5) * 0x1.0p-53;
    };
    std::vector<double> noise(n);
    for (std::size_t i = 0; i < n; i += 2) {
        const double radius = std::sqrt(-2.0 * std::log(uniform_open()));
        const double angle = 2.0 * kPi * uniform_open();
        noise[i] = radius * std::cos(angle);
        if (i + 1 < n) noise[i + 1] = radius * std::sin(angle);
    }
    return noise;
}

// The spectral synthesis of a map whose PSD (um^4) at (zeta_x, zeta_y) is `psd`.
template <class Psd>
heightmap::HeightMap synthesize_from_psd(const Psd& psd, const SynthesisGrid& grid, std::uint64_t seed) {
    if (grid.nx < heightmap::kMinHeightMapSize || grid.ny < heightmap::kMinHeightMapSize)
        fail("surface size must be at least {} samples per side, got {} x {}", heightmap::kMinHeightMapSize, grid.nx, grid.ny);
    heightmap::require_valid_spacing(grid.spacing_um, "pixel spacing");
    // White noise, its half spectrum, FFTW's plan buffers and the map: about 48 bytes per sample at once.
    require_memory(48.0 * static_cast<double>(grid.nx) * static_cast<double>(grid.ny),
                   fmt::format("a {} x {} surface", grid.nx, grid.ny));
    const std::size_t nx = grid.nx, ny = grid.ny, total = nx * ny;
    auto spectrum = heightmap::forward_fft_2d(white_noise(total, seed), nx, ny);

    const double dzx = 2.0 * kPi / (static_cast<double>(nx) * grid.spacing_um);
    const double dzy = 2.0 * kPi / (static_cast<double>(ny) * grid.spacing_um);
    // A_k / N with A_k = sqrt(N P dzeta^2): the 1/N of the inverse transform folded in.
    const double scale = std::sqrt(dzx * dzy / static_cast<double>(total));
    const std::size_t half = nx / 2 + 1;
    for (std::size_t ky = 0; ky < ny; ++ky) {
        const double zy = static_cast<double>(heightmap::signed_frequency_index(ky, ny)) * dzy;
        for (std::size_t kx = 0; kx < half; ++kx) {
            const double zx = static_cast<double>(kx) * dzx;
            const double p = (kx == 0 && ky == 0) ? 0.0 : psd(zx, zy);
            spectrum[ky * half + kx] *= scale * std::sqrt(p);
        }
    }
    return heightmap::HeightMap(nx, ny, grid.spacing_um, grid.spacing_um,
                                heightmap::inverse_fft_2d(std::move(spectrum), nx, ny),
                                "synthesized surface");
}
}  // namespace

heightmap::HeightMap synthesize_surface(const RadialStatistics& statistics, const SynthesisGrid& grid, std::uint64_t seed) {
    return synthesize_from_psd([&](double zx, double zy) { return statistics.psd(std::hypot(zx, zy)); }, grid, seed);
}

heightmap::HeightMap synthesize_surface(const EllipticalStatistics& statistics, const SynthesisGrid& grid, std::uint64_t seed) {
    const double variance = statistics.sigma_h() * statistics.sigma_h();
    return synthesize_from_psd([&](double zx, double zy) { return variance * statistics.psd_unit({zx, zy}); }, grid,
                               seed);
}

double profile_psd(const RadialStatistics& statistics, double zeta_x) {
    require_finite(zeta_x, "profile PSD frequency");
    // zeta_y = c u / (1 - u) maps [0, 1) onto [0, inf); c near the PSD's knee keeps the integrand smooth in u.
    const double c = std::max(std::abs(zeta_x), 1.0 / statistics.correlation_length());
    const auto integrand = [&](double u) {
        if (u >= 1.0) return 0.0;
        const double zeta_y = c * u / (1.0 - u);
        return statistics.psd(std::hypot(zeta_x, zeta_y)) * c / ((1.0 - u) * (1.0 - u));
    };
    return 2.0 * math::integrate_adaptive(integrand, 0.0, 1.0, 1e-10);
}

std::vector<double> synthesize_profile(const RadialStatistics& statistics, std::size_t n, double spacing_um,
                                       std::uint64_t seed, ProfileMean mean) {
    if (n < 4) fail("profile length must be at least 4 samples, got {}", n);
    heightmap::require_valid_spacing(spacing_um, "profile spacing");
    require_memory(48.0 * static_cast<double>(n), fmt::format("a profile of {} samples", n));
    auto spectrum = heightmap::forward_fft_2d(white_noise(n, seed), n, 1);
    const double dz = 2.0 * kPi / (static_cast<double>(n) * spacing_um);
    const double scale = std::sqrt(dz / static_cast<double>(n));  // A_k / N with A_k = sqrt(N P1 dzeta)
    for (std::size_t kx = 0; kx < spectrum.size(); ++kx)
        spectrum[kx] *= kx == 0 && mean == ProfileMean::zero
                            ? 0.0
                            : scale * std::sqrt(profile_psd(statistics, static_cast<double>(kx) * dz));
    return heightmap::inverse_fft_2d(std::move(spectrum), n, 1);
}

}  // namespace surfscatter::surface
