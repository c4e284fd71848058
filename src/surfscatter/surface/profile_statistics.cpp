#include "surfscatter/surface/profile_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/ring_psd.hpp"

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

ProfilePeriodogram profile_periodogram(const heightmap::LineScan& scan, heightmap::Form form) {
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
    ProfilePeriodogram out;
    out.dzeta = 2.0 * kPi / (static_cast<double>(n) * scan.spacing_um);
    out.points = n;
    out.rms_um = moments.rms_height_um;
    out.origin = scan.origin;
    const double scale = scan.spacing_um / (2.0 * kPi * window_power);
    for (std::size_t k = 0; k <= n / 2; ++k) out.psd.push_back(std::norm(spectrum[k]) * scale);
    return out;
}

double ProfilePeriodogram::sum() const {
    double total = psd[0];
    for (std::size_t k = 1; k < psd.size(); ++k) total += (2 * k == points ? 1.0 : 2.0) * psd[k];
    return total * dzeta;
}

RadialPsd estimate_profile_psd(const heightmap::LineScan& scan, heightmap::Form form) {
    const ProfilePeriodogram p = profile_periodogram(scan, form);
    RadialPsd out;
    out.window = Window::hann;
    out.dzeta = kProfileBandBins * p.dzeta;
    // Ring 0 holds the zero frequency alone (as a map's centre ring), ring b >= 1 frequencies k of
    // (b - 1) B + 1 .. b B; each frequency counts twice (+-k, Hermitian mirrors), as in a map's rings.
    out.zeta.push_back(0.0);
    out.psd.push_back(p.psd[0]);
    out.count.push_back(1.0);
    const std::size_t top = p.points / 2;
    for (std::size_t first = 1; first + kProfileBandBins - 1 <= top; first += kProfileBandBins) {
        double zeta = 0.0, psd = 0.0;
        for (std::size_t k = first; k < first + kProfileBandBins; ++k) {
            zeta += static_cast<double>(k) * p.dzeta;
            psd += p.psd[k];
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

namespace surfscatter::surface {

namespace {

constexpr int kAbelPoints = 8;          // Gauss-Legendre points per power-law segment of P1 (in t)
constexpr double kTailStep = 0.5;       // t-width of the tail's pieces
constexpr double kTailDecay = 40.0;     // the tail is integrated until (a + 1) t has grown by this (e^-40)

const math::GaussLegendreRule& abel_rule() {
    static const math::GaussLegendreRule rule(kAbelPoints);
    return rule;
}

// int_{t0}^{t1} f(t) dt by the rule mapped from [-1, 1].
template <typename F>
double integrate_gl(const F& f, double t0, double t1) {
    const math::GaussLegendreRule& rule = abel_rule();
    const double half = 0.5 * (t1 - t0), middle = 0.5 * (t1 + t0);
    double sum = 0.0;
    for (std::size_t i = 0; i < rule.nodes.size(); ++i) sum += rule.weights[i] * f(middle + half * rule.nodes[i]);
    return sum * half;
}

}  // namespace

ProfileStatistics::ProfileStatistics(const heightmap::LineScan& scan, heightmap::Form form)
    : ProfileStatistics(profile_periodogram(scan, form)) {}

ProfileStatistics::ProfileStatistics(ProfilePeriodogram p) : dzeta_(p.dzeta), rms_um_(p.rms_um) {
    const std::size_t top = p.psd.size() - 1;
    if (top < 2 * kProfileBandBins)
        fail("{}: {} bins: a profile's measured spectrum needs at least {}", p.origin, top, 2 * kProfileBandBins);
    if (!(rms_um_ > 0.0)) fail("{}: no roughness is left after removing the form: rms height 0", p.origin);
    nyquist_ = static_cast<double>(top) * dzeta_;
    // Window correction: the periodogram's total scaled to the profile's variance (as a map's, map_statistics.hpp).
    const double held = p.sum();
    if (!(held > 0.0)) fail("{}: its periodogram holds no power", p.origin);
    window_scale_ = rms_um_ * rms_um_ / held;
    for (double& v : p.psd) v *= window_scale_;
    for (std::size_t k = 1; k <= top; ++k) bin_variance_.push_back((2 * k == p.points ? 1.0 : 2.0) * p.psd[k] * dzeta_);
    // Bands: kProfileBandBins bins, widening to kProfileBandWidth of their frequency.
    for (std::size_t first = 1; first <= top;) {
        const std::size_t width = std::max<std::size_t>(
            kProfileBandBins, static_cast<std::size_t>(std::ceil(kProfileBandWidth * static_cast<double>(first))));
        std::size_t last = std::min(top, first + width - 1);
        if (top - last < width / 2) last = top;  // no short band at the top
        double zeta = 0.0, psd = 0.0;
        for (std::size_t k = first; k <= last; ++k) zeta += static_cast<double>(k), psd += p.psd[k];
        const double bins = static_cast<double>(last - first + 1);
        if (psd > 0.0) {
            band_zeta_.push_back(zeta / bins * dzeta_);
            band_psd_.push_back(psd / bins);
        }
        first = last + 1;
    }
    if (band_zeta_.size() < 2) fail("{}: fewer than 2 bands of its spectrum hold power", p.origin);
    // The tail: the least-squares power law over the last octave's bands (at least the last two), not rising.
    const double top_band = band_zeta_.back();
    double sx = 0, sy = 0, sxx = 0, sxy = 0, count = 0;
    for (std::size_t j = 0; j < band_zeta_.size(); ++j)
        if (band_zeta_[j] >= 0.5 * top_band || j + 2 >= band_zeta_.size()) {
            const double x = std::log(band_zeta_[j]), y = std::log(band_psd_[j]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, count += 1;
        }
    tail_power_ = std::max(0.0, -(count * sxy - sx * sy) / (count * sxx - sx * sx));
    // The slopes d ln P1 / d ln u at the band centres: the secants' mean weighted by the opposite interval (exact for
    // a parabola in ln u), the last band's the tail's, the first band's that of the even parabola P1(0) - b u^2
    // through the first two bands (b >= 0), which continues P1 below the first centre (abel_inverse()).
    const std::size_t bands = band_zeta_.size();
    for (std::size_t j = 0; j < bands; ++j) {
        const auto secant = [&](std::size_t i) {
            return std::log(band_psd_[i + 1] / band_psd_[i]) / std::log(band_zeta_[i + 1] / band_zeta_[i]);
        };
        if (j == 0) {
            const double u0 = band_zeta_[0], u1 = band_zeta_[1];
            parabola_ = std::max(0.0, (band_psd_[0] - band_psd_[1]) / (u1 * u1 - u0 * u0));
            band_slope_.push_back(-2.0 * parabola_ * u0 * u0 / band_psd_[0]);
        } else if (j + 1 == bands) {
            band_slope_.push_back(-tail_power_);
        } else {
            const double before = std::log(band_zeta_[j] / band_zeta_[j - 1]), after = std::log(band_zeta_[j + 1] / band_zeta_[j]);
            band_slope_.push_back((after * secant(j - 1) + before * secant(j)) / (before + after));
        }
    }
    // P at the profile's bins; P(0) from the transform's limit. A bin where P came out <= 0 is skipped: ln P runs
    // linearly across it between its positive neighbours, written into the bin so that the grid stays uniform (the
    // models read P in O(1): MapRingPsd's first guess of the segment is then exact).
    const double dc = abel_inverse(0.0);
    std::vector<double> zeta, psd, log_psd;
    std::vector<std::size_t> kept;
    for (std::size_t k = 1; k <= top; ++k) {
        zeta.push_back(static_cast<double>(k) * dzeta_);
        const double value = abel_inverse(zeta.back());
        log_psd.push_back(value > 0.0 && std::isfinite(value) ? std::log(value) : 0.0);
        if (value > 0.0 && std::isfinite(value)) kept.push_back(zeta.size() - 1);
    }
    nodes_ = zeta.size();
    clipped_ = nodes_ - kept.size();
    if (kept.size() < 4)
        fail("{}: the inverse Abel transform of its spectrum is positive at {} frequencies; the measured route needs "
             "at least 4", p.origin, kept.size());
    for (std::size_t i = 0, next = 0; i < nodes_; ++i) {
        while (next < kept.size() && kept[next] < i) ++next;
        if (next < kept.size() && kept[next] == i) continue;
        const std::size_t hi = next < kept.size() ? kept[next] : kept.back(), lo = next > 0 ? kept[next - 1] : hi;
        const double w = hi == lo ? 0.0 : static_cast<double>(i - lo) / static_cast<double>(hi - lo);
        log_psd[i] = hi == lo ? log_psd[hi] : (1 - w) * log_psd[lo] + w * log_psd[hi];
    }
    for (double v : log_psd) psd.push_back(std::exp(v));
    // The model carries the profile's variance, as a map's carries the map's (MapStatistics::band_scale()): the one
    // factor that makes it so corrects what the skipped bins and the continuations add or leave out.
    double p0 = dc > 0.0 ? dc : psd.front();
    band_scale_ = rms_um_ * rms_um_ / std::pow(MapRingPsd(p0, zeta, psd, nyquist_, "unscaled").sigma_h(), 2);
    p0 *= band_scale_;
    for (double& v : psd) v *= band_scale_;
    std::string key = fmt::format("profile({:.17g};{:.17g};", nyquist_, p0);
    for (std::size_t i = 0; i < zeta.size(); ++i) key += fmt::format("{:.17g}:{:.17g};", zeta[i], psd[i]);
    psd_ = std::make_shared<const MapRingPsd>(p0, std::move(zeta), std::move(psd), nyquist_, key + ")");
}

double ProfileStatistics::abel_inverse(double z) const {
    // P1 between band centres j and j + 1: ln P1 a cubic Hermite polynomial in s = ln u through the centres with
    // their slopes (so that P1' is continuous and P has no cusps); P1'(u) = P1 (d ln P1 / ds) / u.
    const std::size_t bands = band_zeta_.size();
    const auto derivative = [&](std::size_t j, double u) {
        const double s0 = std::log(band_zeta_[j]), width = std::log(band_zeta_[j + 1]) - s0;
        const double t = (std::log(u) - s0) / width, y0 = std::log(band_psd_[j]), y1 = std::log(band_psd_[j + 1]);
        const double m0 = band_slope_[j] * width, m1 = band_slope_[j + 1] * width;
        const double y = (2 * t * t * t - 3 * t * t + 1) * y0 + (t * t * t - 2 * t * t + t) * m0 +
                         (-2 * t * t * t + 3 * t * t) * y1 + (t * t * t - t * t) * m1;
        const double dy = ((6 * t * t - 6 * t) * (y0 - y1) + (3 * t * t - 4 * t + 1) * m0 + (3 * t * t - 2 * t) * m1) / width;
        return std::exp(y) * dy / u;
    };
    const double u_top = band_zeta_.back(), p_top = band_psd_.back();
    const auto tail = [&](double u) { return -tail_power_ * p_top * std::pow(u / u_top, -tail_power_) / u; };
    double sum = 0.0;
    const auto segment = [&](double lo, double hi, const auto& slope) {
        if (hi <= std::max(lo, z)) return;
        lo = std::max(lo, z);
        if (z == 0.0)  // int P1'(u) / u du over s = ln u
            sum += integrate_gl([&](double s) { return slope(std::exp(s)); }, std::log(lo), std::log(hi));
        else           // u = z cosh t: du / sqrt(u^2 - z^2) = dt
            sum += integrate_gl([&](double t) { return slope(z * std::cosh(t)); }, std::acosh(lo / z), std::acosh(hi / z));
    };
    // Below the first centre u0 the even parabola P1(u0) + b (u0^2 - u^2): P1'(u) = -2 b u, closed-form integrals.
    const double u0 = band_zeta_.front();
    if (z < u0) sum -= 2.0 * parabola_ * (z == 0.0 ? u0 : std::sqrt(u0 * u0 - z * z));
    for (std::size_t j = 0; j + 1 < bands; ++j)
        segment(band_zeta_[j], band_zeta_[j + 1], [&](double u) { return derivative(j, u); });
    // The tail, in pieces of kTailStep in ln u (~ t where u >> z) until its integrand has fallen by e^-kTailDecay.
    if (tail_power_ > 0.0) {
        const double reach = kTailDecay / (tail_power_ + 1.0);
        for (double s = 0.0; s < reach; s += kTailStep) segment(u_top * std::exp(s), u_top * std::exp(s + kTailStep), tail);
    }
    return -sum / kPi;
}

double ProfileStatistics::sigma_relative_error() const {
    // Each bin pair (+-k) of the rectangular periodogram is one exponential sample of its variance (the window
    // correction makes sigma the unweighted rms, as for a map: MapStatistics::sigma_relative_error()).
    double mass = 0.0, variance = 0.0;
    for (double m : bin_variance_) mass += m, variance += m * m;
    return mass > 0.0 ? 0.5 * std::sqrt(variance) / mass : 0.0;
}

std::string measured_profile_note(const ProfileStatistics& s, const std::string& origin) {
    return fmt::format(
        "measured profile PSD of {}: {}; the 2-D PSD is the inverse Abel transform of the profile's Hann-windowed 1-D "
        "PSD in {} bands ({} bins, widening to {:.0f} % of their frequency), continued below the first band ({:.3g} "
        "rad/um) as an even parabola with its value and slope and beyond the last as zeta^-{:.3g} (the last octave's "
        "power law; only the transform near Nyquist reads it); used over zeta {:.3g} .. {:.3g} rad/um (periods {:.3g} "
        ".. {:.3g} um) and rolled off as zeta^-200 beyond ({:.2g} % of sigma^2); {} of {} frequencies where the "
        "transform of the noisy spectrum came out <= 0 skipped; scaled by {:.4g} to carry the profile's variance: "
        "model sigma {:.6g} um, the profile's rms {:.6g} um (standard error of sigma {:.2g} %)",
        origin, kMeasuredIsotropyNote, s.band_zeta().size(), kProfileBandBins, 100 * kProfileBandWidth,
        s.band_zeta().front(), s.tail_power(), s.first_ring(), s.nyquist(), kTwoPi / s.nyquist(),
        kTwoPi / s.first_ring(), 100.0 * s.above_band_fraction(), s.clipped_nodes(), s.nodes(), s.band_scale(),
        s.sigma_h(), s.map_rms(), 100.0 * s.sigma_relative_error());
}

}  // namespace surfscatter::surface
