#pragma once
// Two-dimensional real FFTs of height maps through FFTW3 (double precision, FFTW_ESTIMATE plans so that results
// do not depend on timing). Layout: real data ny x nx row-major; half spectrum ny x (nx/2 + 1), entry
// [ky * (nx/2 + 1) + kx], unnormalised (forward sum_n h_n e^{-2 pi i k.n/N}; inverse without the 1/N).
#include <complex>
#include <cstddef>
#include <vector>

namespace surfscatter::heightmap {

std::vector<std::complex<double>> forward_fft_2d(const std::vector<double>& data, std::size_t nx, std::size_t ny);

// Consumes the spectrum (FFTW's complex-to-real transform overwrites its input).
std::vector<double> inverse_fft_2d(std::vector<std::complex<double>> spectrum, std::size_t nx, std::size_t ny);

// Linear (non-cyclic) autocorrelation A(tx, ty) = sum_n v(n) v(n + t) of an nx x ny array for every lag
// |tx| < nx, |ty| < ny, by FFT of the array zero-padded to 2nx x 2ny: entry [(ty mod 2ny) * 2nx + (tx mod 2nx)].
// Absolute rounding error ~1e-16 sum v^2 per lag.
std::vector<double> linear_autocorrelation(const std::vector<double>& values, std::size_t nx, std::size_t ny);

// Signed frequency index of DFT bin k for a transform of length n: 0, 1, ..., n/2, -(n - n/2 - 1), ..., -1.
inline long signed_frequency_index(std::size_t k, std::size_t n) {
    return k <= n / 2 ? static_cast<long>(k) : static_cast<long>(k) - static_cast<long>(n);
}

}  // namespace surfscatter::heightmap
