#include "surfscatter/heightmap/gaussian_filter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"

namespace surfscatter::heightmap {

namespace {

constexpr double kPi = std::numbers::pi;
const double kAlpha = std::sqrt(std::numbers::ln2 / kPi);
// Reach of the weighting function in units of alpha lc: exp(-pi x^2) = 1e-16 at x = sqrt(16 ln 10 / pi).
const double kReach = std::sqrt(16.0 * std::numbers::ln10 / kPi);
// The 2-D Hann window correlates each periodogram bin with its 5 x 5 neighbours: sum rho^2 = (35/18)^2 (35/18 along
// each axis), so N lattice points of a smooth spectrum hold N / (2 (35/18)^2) independent samples of the variance.
constexpr double kHannCorrelation = (35.0 / 18.0) * (35.0 / 18.0);

// Smallest n' >= n whose only prime factors are 2, 3, 5, 7 (FFTW's fast sizes).
std::size_t fft_size(std::size_t n) {
    for (std::size_t m = n;; ++m) {
        std::size_t r = m;
        for (std::size_t p : {2, 3, 5, 7})
            while (r % p == 0) r /= p;
        if (r == 1) return m;
    }
}

void require_nesting_index(const HeightMap& map, double lc, const char* what) {
    const double spacing = std::max(map.spacing_x(), map.spacing_y());
    if (!(std::isfinite(lc) && lc >= kMinNestingPixels * spacing))
        fail("{} {} um for {}: must be at least {:g} pixel spacings ({:.4g} um), the finest nesting index the grid "
             "samples (ISO 25178-3)", what, lc, map.origin(), kMinNestingPixels, kMinNestingPixels * spacing);
}

HeightMap lowpass(const HeightMap& map, double lc) {
    const std::size_t nx = map.nx(), ny = map.ny();
    const double b = kAlpha * lc;
    const std::size_t kx = std::min(nx - 1, static_cast<std::size_t>(std::ceil(kReach * b / map.spacing_x())));
    const std::size_t ky = std::min(ny - 1, static_cast<std::size_t>(std::ceil(kReach * b / map.spacing_y())));
    // Zero-padded by the reach: the cyclic convolution of size (px, py) is the linear one on the map.
    const std::size_t px = fft_size(nx + kx), py = fft_size(ny + ky);
    std::vector<double> weighted(px * py, 0.0), mask(px * py, 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            if (map.valid(ix, iy)) {
                weighted[iy * px + ix] = map(ix, iy);
                mask[iy * px + ix] = 1.0;
            }
    // s sampled at lags -k .. k along each axis, at index lag mod p. It is separable and even, so its 2-D DFT is the
    // product of the two axes' real 1-D DFTs.
    auto axis = [&](std::size_t reach, std::size_t p, double spacing) {
        std::vector<double> s(p, 0.0);
        for (std::size_t t = 0; t <= reach; ++t) {
            const double x = static_cast<double>(t) * spacing / b;
            s[t] = s[(p - t) % p] = std::exp(-kPi * x * x);
        }
        return forward_fft_2d(s, p, 1);  // bins 0 .. p/2; bin p - k equals bin k
    };
    const auto sx = axis(kx, px, map.spacing_x()), sy = axis(ky, py, map.spacing_y());
    const std::size_t half = px / 2 + 1;
    std::vector<double> sk(half * py);
    for (std::size_t iy = 0; iy < py; ++iy)
        for (std::size_t ix = 0; ix < half; ++ix) sk[iy * half + ix] = sx[ix].real() * sy[std::min(iy, py - iy)].real();
    auto sh = forward_fft_2d(weighted, px, py);
    auto sm = forward_fft_2d(mask, px, py);
    for (std::size_t i = 0; i < sk.size(); ++i) {
        sh[i] *= sk[i];
        sm[i] *= sk[i];
    }
    const std::vector<double> numerator = inverse_fft_2d(std::move(sh), px, py);
    const std::vector<double> denominator = inverse_fft_2d(std::move(sm), px, py);
    std::vector<double> mean(map.size(), 0.0);
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix)
            // A valid point's own weight (1 before the FFT's scaling) keeps the denominator far from 0.
            if (map.valid(ix, iy)) mean[iy * nx + ix] = numerator[iy * px + ix] / denominator[iy * px + ix];
    return map.with_heights(std::move(mean));
}

HeightMap difference(const HeightMap& a, const HeightMap& b) {
    std::vector<double> h = a.heights();
    for (std::size_t i = 0; i < h.size(); ++i) h[i] -= b.heights()[i];
    return a.with_heights(std::move(h));
}

// L-filter's power transmission at spatial frequency zeta (rad/um): (1 - exp(-pi (alpha lc zeta / 2 pi)^2))^2.
double highpass_power(double zeta, double lc) {
    if (lc <= 0) return 1.0;
    const double x = kAlpha * lc * zeta / (2.0 * kPi);
    const double t = -std::expm1(-kPi * x * x);
    return t * t;
}

// 1-2-5 series from the largest value <= `top` down to the smallest >= `bottom`, longest first.
std::vector<double> series_125(double bottom, double top) {
    std::vector<double> out;
    for (double decade = std::pow(10.0, std::floor(std::log10(top))); decade * 5 >= bottom; decade /= 10)
        for (double m : {5.0, 2.0, 1.0}) {
            const double v = m * decade;
            if (v <= top * (1 + 1e-12) && v >= bottom * (1 - 1e-12)) out.push_back(v);
        }
    return out;
}

}  // namespace

HeightMap gaussian_lowpass(const HeightMap& map, double nesting_index_um) {
    require_nesting_index(map, nesting_index_um, "Gaussian filter nesting index");
    return lowpass(map, nesting_index_um);
}

Filtered s_filter(const HeightMap& map, double lambda_s_um) {
    require_nesting_index(map, lambda_s_um, "lambda_s");
    HeightMap mean = lowpass(map, lambda_s_um);
    HeightMap removed = difference(map, mean);
    return {std::move(mean), std::move(removed)};
}

Filtered l_filter(const HeightMap& map, double lambda_c_um) {
    require_nesting_index(map, lambda_c_um, "lambda_c");
    HeightMap waviness = lowpass(map, lambda_c_um);
    HeightMap roughness = difference(map, waviness);
    return {std::move(roughness), std::move(waviness)};
}

double sigma_relative_error(const HeightMap& map, double lambda_c_um) {
    if (!(std::isfinite(lambda_c_um) && lambda_c_um >= 0))
        fail("lambda_c {} um for {}: must be a finite length >= 0 (0: no L-filter)", lambda_c_um, map.origin());
    const std::size_t nx = map.nx(), ny = map.ny();
    double mean = 0;
    for (std::size_t i = 0; i < map.size(); ++i) mean += map.valid(i) ? map.heights()[i] : 0.0;
    mean /= static_cast<double>(map.valid_count());
    auto hann = [](std::size_t i, std::size_t n) {
        const double s = std::sin(kPi * (static_cast<double>(i) + 0.5) / static_cast<double>(n));
        return s * s;
    };
    std::vector<double> values(map.size(), 0.0);
    double window_power = 0, valid_power = 0;
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < nx; ++ix) {
            const double w = hann(ix, nx) * hann(iy, ny);
            window_power += w * w;
            if (!map.valid(ix, iy)) continue;
            values[iy * nx + ix] = w * (map(ix, iy) - mean);
            valid_power += w * w;
        }
    const auto spectrum = forward_fft_2d(values, nx, ny);
    const double dzx = 2 * kPi / map.width(), dzy = 2 * kPi / map.height(), dz = std::max(dzx, dzy);
    const double nyquist = std::min(dzx * static_cast<double>(nx / 2), dzy * static_cast<double>(ny / 2));
    const std::size_t rings = static_cast<std::size_t>(std::max(1.0, std::floor(nyquist / dz - 0.5) + 1));
    std::vector<double> power(rings, 0.0), count(rings, 0.0);
    const std::size_t half = nx / 2 + 1;
    for (std::size_t iy = 0; iy < ny; ++iy)
        for (std::size_t ix = 0; ix < half; ++ix) {
            const double zx = static_cast<double>(ix) * dzx;
            const double zy = static_cast<double>(signed_frequency_index(iy, ny)) * dzy;
            const double zeta = std::hypot(zx, zy);
            const auto ring = static_cast<std::size_t>(std::floor(zeta / dz + 0.5));
            if (ring == 0 || ring >= rings) continue;
            // Points of the full plane this half-plane bin stands for.
            const double m = (ix == 0 || (nx % 2 == 0 && ix == nx / 2)) ? 1.0 : 2.0;
            power[ring] += m * std::norm(spectrum[iy * half + ix]) * highpass_power(zeta, lambda_c_um);
            count[ring] += m;
        }
    double mass = 0, variance = 0;
    const double valid_weight = valid_power / window_power;
    for (std::size_t k = 1; k < rings; ++k) {
        if (count[k] == 0) continue;
        mass += power[k];
        variance += power[k] * power[k] / (count[k] * valid_weight / (2.0 * kHannCorrelation));
    }
    return mass > 0 ? 0.5 * std::sqrt(variance) / mass : 0.0;
}

double default_lambda_c(const HeightMap& map, std::string* reason, double shortest_um) {
    auto say = [&](std::string text) {
        if (reason) *reason = std::move(text);
    };
    const double error = sigma_relative_error(map);
    if (error <= kLambdaCSigmaError) {
        say(fmt::format("no L-filter: the map resolves its spectrum (standard error of sigma {:.2g} % <= {:g} %)",
                        100 * error, 100 * kLambdaCSigmaError));
        return 0.0;
    }
    const double spacing = std::max(map.spacing_x(), map.spacing_y());
    const std::vector<double> series =
        series_125(std::max(kMinNestingPixels * spacing, shortest_um), std::max(map.width(), map.height()));
    // The longest candidate whose rings, times the filter's power transmission, reach the error starts the search;
    // the filtered map's own error decides (it is the lower of the two on the real files: the Hann window's leakage
    // from the removed periods goes with them): longer ones while it holds, else shorter ones until it does.
    std::size_t i = 0;
    while (i < series.size() && sigma_relative_error(map, series[i]) > kLambdaCSigmaError) ++i;
    auto filtered_error = [&](std::size_t k) { return sigma_relative_error(l_filter(map, series[k]).kept); };
    std::size_t chosen = series.size();
    double filtered = 0;
    if (i < series.size() && (filtered = filtered_error(i)) <= kLambdaCSigmaError) {
        chosen = i;
        for (double e; chosen > 0 && (e = filtered_error(chosen - 1)) <= kLambdaCSigmaError;) --chosen, filtered = e;
    } else {
        for (std::size_t k = i + 1; k < series.size(); ++k)
            if ((filtered = filtered_error(k)) <= kLambdaCSigmaError) {
                chosen = k;
                break;
            }
    }
    if (chosen < series.size()) {
        say(fmt::format("lambda_c {:g} um: the longest of the 1-2-5 series at which sigma's standard error is <= {:g} "
                        "% ({:.2g} % after the filter, {:.2g} % without it: the longest periods hold the variance)",
                        series[chosen], 100 * kLambdaCSigmaError, 100 * filtered, 100 * error));
        return series[chosen];
    }
    say(fmt::format("no L-filter: sigma's standard error is {:.2g} % and no nesting index of the 1-2-5 series from {:g} "
                    "um to the map's size brings it to {:g} %", 100 * error,
                    std::max(kMinNestingPixels * spacing, shortest_um), 100 * kLambdaCSigmaError));
    return 0.0;
}

}  // namespace surfscatter::heightmap
