#include "surfscatter/surface/profile_statistics.hpp"

#include <cmath>
#include <complex>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

ProfileMoments profile_moments(const heightmap::LineScan& scan, heightmap::Form form) {
    if (form != heightmap::Form::none && form != heightmap::Form::plane)
        fail("{}: a profile's form is none (its mean) or plane (a line), got {}", scan.origin, heightmap::to_string(form));
    const std::size_t n = scan.size();
    const auto valid = [&](std::size_t i) { return scan.validity.empty() || scan.validity[i] != 0; };
    // Least-squares line (or mean) over the valid points, x in units of the spacing about the middle.
    double s0 = 0, s1 = 0, s2 = 0, sh = 0, sxh = 0;
    const double middle = 0.5 * static_cast<double>(n - 1);
    for (std::size_t i = 0; i < n; ++i) {
        if (!valid(i)) continue;
        const double x = static_cast<double>(i) - middle;
        s0 += 1, s1 += x, s2 += x * x, sh += scan.heights_um[i], sxh += x * scan.heights_um[i];
    }
    if (s0 < 2) fail("{}: a profile needs at least 2 valid points, it has {}", scan.origin, s0);
    double slope = 0.0, mean = sh / s0;
    if (form == heightmap::Form::plane) {
        const double det = s0 * s2 - s1 * s1;
        slope = (s0 * sxh - s1 * sh) / det;
        mean = (sh - slope * s1) / s0;
    }
    ProfileMoments out;
    out.heights_um.assign(n, 0.0);
    double sum2 = 0.0;
    for (std::size_t i = 0; i < n; ++i)
        if (valid(i)) {
            out.heights_um[i] = scan.heights_um[i] - mean - slope * (static_cast<double>(i) - middle);
            sum2 += out.heights_um[i] * out.heights_um[i];
        }
    out.rms_height_um = std::sqrt(sum2 / s0);
    double slopes2 = 0.0;
    std::size_t slopes = 0;
    for (std::size_t i = 1; i + 1 < n; ++i)
        if (valid(i - 1) && valid(i + 1)) {
            const double d = (out.heights_um[i + 1] - out.heights_um[i - 1]) / (2.0 * scan.spacing_um);
            slopes2 += d * d, ++slopes;
        }
    out.rms_slope = slopes > 0 ? std::sqrt(slopes2 / static_cast<double>(slopes)) : 0.0;
    return out;
}

RadialPsd estimate_profile_psd(const heightmap::LineScan& scan, heightmap::Form form) {
    const std::size_t n = scan.size();
    if (n < 16) fail("{}: a profile of {} points: its PSD needs at least 16", scan.origin, n);
    if (scan.valid_count() != n)
        fail("{}: the profile has {} invalid points of {}: its 1-D PSD is estimated on fully valid profiles only",
             scan.origin, n - scan.valid_count(), n);
    const ProfileMoments moments = profile_moments(scan, form);
    std::vector<double> weighted(n);
    double window_power = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
        const double w = window_value(Window::hann, i, n);
        weighted[i] = w * moments.heights_um[i];
        window_power += w * w;
    }
    const auto spectrum = heightmap::forward_fft_2d(weighted, n, 1);
    const double dzeta = 2.0 * kPi / (static_cast<double>(n) * scan.spacing_um);
    const double scale = scan.spacing_um / (2.0 * kPi * window_power);
    RadialPsd out;
    out.window = Window::hann;
    out.dzeta = kProfileBandBins * dzeta;
    // Ring 0 holds the zero frequency alone (as a map's centre ring), ring b >= 1 frequencies k of
    // (b - 1) B + 1 .. b B; each frequency counts twice (+-k, Hermitian mirrors), as in a map's rings.
    out.zeta.push_back(0.0);
    out.psd.push_back(std::norm(spectrum[0]) * scale);
    out.count.push_back(1.0);
    const std::size_t top = n / 2;
    for (std::size_t first = 1; first + kProfileBandBins - 1 <= top; first += kProfileBandBins) {
        double zeta = 0.0, psd = 0.0;
        for (std::size_t k = first; k < first + kProfileBandBins; ++k) {
            zeta += static_cast<double>(k) * dzeta;
            psd += std::norm(spectrum[k]) * scale;
        }
        out.zeta.push_back(zeta / kProfileBandBins);
        out.psd.push_back(psd / kProfileBandBins);
        out.count.push_back(2.0 * kProfileBandBins);
    }
    return out;
}

ProfileFit fit_profile(const heightmap::LineScan& scan, KcFitOptions options) {
    options.profile = true;
    ProfileFit out;
    const ProfileMoments moments = profile_moments(scan, options.form);
    out.rms_height_um = moments.rms_height_um;
    out.rms_slope = moments.rms_slope;
    out.length_um = scan.length_um();
    out.nyquist = kPi / scan.spacing_um;
    out.psd = estimate_profile_psd(scan, options.form);
    out.kc = fit_kc(out.psd, out.nyquist, options);
    const KCorrelation model(out.kc.sigma_h_um, out.kc.corr_length_um, out.kc.gamma);
    double fitted = 0.0, held = 0.0;
    const double bin = out.psd.dzeta / kProfileBandBins;
    for (std::size_t b = 1; b < out.psd.zeta.size(); ++b) {
        fitted += 2.0 * kProfileBandBins * model.sigma_h() * model.sigma_h() * model.profile_psd_unit(out.psd.zeta[b]);
        held += 2.0 * kProfileBandBins * out.psd.psd[b];
    }
    out.fit_band_rms_um = std::sqrt(fitted * bin);
    out.profile_band_rms_um = std::sqrt(held * bin);
    return out;
}

}  // namespace surfscatter::surface
