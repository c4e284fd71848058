#include "surfscatter/surface/profile_statistics.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include <Eigen/Core>
#include <unsupported/Eigen/NonLinearOptimization>
#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/least_squares_functor.hpp"
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

constexpr int kAbelPoints = 12;        // Gauss-Legendre points per knot interval (in t) of the forward transform
constexpr double kTailStep = 1.0;      // t-width of the tail's pieces
constexpr double kTailDecay = 40.0;    // the tail is integrated until its integrand has fallen by e^-kTailDecay

const math::GaussLegendreRule& abel_rule() {
    static const math::GaussLegendreRule rule(kAbelPoints);
    return rule;
}

// The knots' bins: 1, then each max(min(2 x previous, previous + kProfileKnotBins), kProfileKnotRatio x previous)
// (octaves at the lowest bins, where a long first interval put a kink of 9 % into a KC's P), the last at `top`
// (an interval shorter than half the rule's merged into the one before).
std::vector<std::size_t> knot_bins(std::size_t top) {
    std::vector<std::size_t> bins = {1};
    while (bins.back() < top) {
        const std::size_t last = bins.back();
        const auto next = std::max(std::min(2 * last, last + kProfileKnotBins),
                                   static_cast<std::size_t>(std::ceil(kProfileKnotRatio * static_cast<double>(last))));
        bins.push_back(std::min(next, top));
    }
    const std::size_t n = bins.size();
    if (n > 2 && 2 * (bins[n - 1] - bins[n - 2]) < std::max(kProfileKnotBins, bins[n - 2] / 5)) bins.erase(bins.end() - 2);
    return bins;
}

// The power a of P ~ z^-a beyond the last knot: the last interval's, at least kProfileMinTailPower (so that the
// forward transform converges).
double profile_tail_power(const std::vector<double>& log_knots, const std::vector<double>& log_psd) {
    const std::size_t m = log_knots.size() - 1;
    const double slope = (log_psd[m] - log_psd[m - 1]) / (log_knots[m] - log_knots[m - 1]);
    return std::max(kProfileMinTailPower, -slope);
}

// P(z) of ln P piecewise linear in ln z at the knots, constant below the first and z^-a beyond the last; its
// gradient in the knots' ln P if asked.
double knot_psd(const std::vector<double>& log_knots, const std::vector<double>& log_psd, double z,
                std::vector<double>* gradient) {
    const std::size_t m = log_knots.size() - 1;
    if (gradient) std::fill(gradient->begin(), gradient->end(), 0.0);
    const double s = z > 0.0 ? std::log(z) : -std::numeric_limits<double>::infinity();
    if (s <= log_knots[0]) {
        if (gradient) (*gradient)[0] = 1.0;
        return std::exp(log_psd[0]);
    }
    if (s >= log_knots[m]) {
        const double slope = (log_psd[m] - log_psd[m - 1]) / (log_knots[m] - log_knots[m - 1]);
        const double x = s - log_knots[m];
        const double value = std::exp(log_psd[m] - profile_tail_power(log_knots, log_psd) * x);
        if (gradient) {
            (*gradient)[m] = value;
            if (-slope > kProfileMinTailPower) {  // the tail's power is the last interval's
                const double w = x / (log_knots[m] - log_knots[m - 1]);
                (*gradient)[m] += value * w, (*gradient)[m - 1] = -value * w;
            }
        }
        return value;
    }
    const std::size_t j = static_cast<std::size_t>(std::upper_bound(log_knots.begin(), log_knots.end(), s) - log_knots.begin()) - 1;
    const double w = (s - log_knots[j]) / (log_knots[j + 1] - log_knots[j]);
    const double value = std::exp((1.0 - w) * log_psd[j] + w * log_psd[j + 1]);
    if (gradient) (*gradient)[j] = value * (1.0 - w), (*gradient)[j + 1] = value * w;
    return value;
}

// The profile PSD P1(u) of the isotropic 2-D PSD knot_psd (the Abel transform), and its gradient if asked.
double abel_forward(const std::vector<double>& log_knots, const std::vector<double>& log_psd, double u,
                    std::vector<double>* gradient) {
    // P1(u) = 2 int_u^inf P(z) z / sqrt(z^2 - u^2) dz = 2 int_0^inf P(u cosh t) u cosh t dt (z = u cosh t), over
    // each knot interval by Gauss-Legendre in t (P a power law there: the integrand is smooth), below the first knot
    // (P constant) in closed form: 2 P0 sqrt(z0^2 - u^2).
    const std::size_t knots = log_knots.size();
    std::vector<double> local(gradient ? knots : 0);
    if (gradient) std::fill(gradient->begin(), gradient->end(), 0.0);
    double sum = 0.0;
    const double z0 = std::exp(log_knots[0]);
    if (u < z0) {
        const double value = 2.0 * std::exp(log_psd[0]) * std::sqrt(z0 * z0 - u * u);
        sum += value;
        if (gradient) (*gradient)[0] += value;
    }
    const math::GaussLegendreRule& rule = abel_rule();
    // At u = 0 the variable is ln z (P1(0) = 2 int P(z) z d ln z), else t.
    const auto z_of = [&](double t) { return u > 0.0 ? u * std::cosh(t) : std::exp(t); };
    const auto piece = [&](double t0, double t1) {
        const double half = 0.5 * (t1 - t0), middle = 0.5 * (t1 + t0);
        for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
            const double z = z_of(middle + half * rule.nodes[i]), weight = 2.0 * rule.weights[i] * half * z;
            sum += weight * knot_psd(log_knots, log_psd, z, gradient ? &local : nullptr);
            if (gradient)
                for (std::size_t j = 0; j < knots; ++j) (*gradient)[j] += weight * local[j];
        }
    };
    const auto t_of = [&](double z) { return u > 0.0 ? (z > u ? std::acosh(z / u) : 0.0) : std::log(z); };
    for (std::size_t j = 0; j + 1 < knots; ++j) {
        const double hi = std::exp(log_knots[j + 1]);
        if (hi > u) piece(t_of(std::exp(log_knots[j])), t_of(hi));
    }
    // Beyond the last knot P ~ z^-a: the integrand falls as e^{(1 - a) t} (t >> 1 or t = ln z).
    const double start = t_of(std::exp(log_knots.back())), a = profile_tail_power(log_knots, log_psd);
    for (double t = start; (t - start) * (a - 1.0) < kTailDecay; t += kTailStep) piece(t, t + kTailStep);
    return sum;
}

// The band means the fit reads, and where the model's band mean is taken: at every bin of a band of up to
// kBandSamples bins, else at the centres of kBandSamples equal parts (a red spectrum's band mean is far above its
// value at the band's centre: at the centre, the fit raised the lowest knots until P held 38 x the variance of hfm-1).
constexpr std::size_t kBandSamples = 8;
struct BandData {
    std::vector<double> zeta, psd, bins;
    std::vector<std::vector<double>> samples;
};

// The forward transform's residuals against the bands (deviance residuals of a band mean of `bins` exponential
// samples: r^2 = 2 n (q - 1 - ln q), q = data / model), and their Jacobian in the knots' ln P.
struct ProfileFitFunctor : DynamicLeastSquaresFunctor {
    const BandData* data;
    const std::vector<double>* log_knots;
    int inputs() const { return static_cast<int>(log_knots->size()); }
    int values() const { return static_cast<int>(data->zeta.size() + log_knots->size() - 1); }
    void evaluate(const Eigen::VectorXd& x, Eigen::VectorXd& residuals, Eigen::MatrixXd* jacobian) const {
        const std::size_t bands = data->zeta.size(), knots = log_knots->size();
        residuals.resize(static_cast<Eigen::Index>(bands + knots - 1));
        if (jacobian) jacobian->setZero(static_cast<Eigen::Index>(bands + knots - 1), static_cast<Eigen::Index>(knots));
        std::vector<double> log_psd(x.data(), x.data() + x.size()), gradient(knots), band_gradient(knots);
        for (std::size_t b = 0; b < bands; ++b) {
            const auto& samples = data->samples[b];
            double model = 0.0;
            if (jacobian) std::fill(band_gradient.begin(), band_gradient.end(), 0.0);
            for (double u : samples) {
                model += abel_forward(*log_knots, log_psd, u, jacobian ? &gradient : nullptr) / samples.size();
                if (jacobian)
                    for (std::size_t j = 0; j < knots; ++j) band_gradient[j] += gradient[j] / samples.size();
            }
            const double q = data->psd[b] / model, n = data->bins[b];
            const double deviance = 2.0 * n * std::max(0.0, q - 1.0 - std::log(q));
            const double r = q >= 1.0 ? std::sqrt(deviance) : -std::sqrt(deviance);
            residuals[static_cast<Eigen::Index>(b)] = r;
            if (!jacobian) continue;
            // dr / d ln M = -n (q - 1) / r, -sqrt(n) at q = 1.
            const double dr = std::abs(q - 1.0) < 1e-8 ? -std::sqrt(n) : -n * (q - 1.0) / r;
            for (std::size_t j = 0; j < knots; ++j)
                (*jacobian)(static_cast<Eigen::Index>(b), static_cast<Eigen::Index>(j)) = dr * band_gradient[j] / model;
        }
        // The smoothness prior, kProfileSmoothing^2 x the bending energy int (d^2 ln P / d ln z^2)^2 d ln z of the
        // knots' polygon: the change of its slope at each knot but the last (at the first, from the constant below
        // it, over as long an interval as the first) over the root of the mean length of the intervals beside it. It
        // ties knots the data hardly constrain to their neighbours.
        const auto& s = *log_knots;
        for (std::size_t j = 0; j + 1 < knots; ++j) {
            const double h1 = s[j + 1] - s[j], slope = (x[static_cast<Eigen::Index>(j + 1)] - x[static_cast<Eigen::Index>(j)]) / h1;
            const double h0 = j > 0 ? s[j] - s[j - 1] : h1;
            const double before = j > 0 ? (x[static_cast<Eigen::Index>(j)] - x[static_cast<Eigen::Index>(j - 1)]) / h0 : 0.0;
            const double weight = kProfileSmoothing / std::sqrt(0.5 * (h0 + h1));
            const auto row = static_cast<Eigen::Index>(bands + j);
            residuals[row] = weight * (slope - before);
            if (!jacobian) continue;
            (*jacobian)(row, static_cast<Eigen::Index>(j + 1)) += weight / h1;
            (*jacobian)(row, static_cast<Eigen::Index>(j)) -= weight / h1;
            if (j > 0) {
                (*jacobian)(row, static_cast<Eigen::Index>(j)) -= weight / h0;
                (*jacobian)(row, static_cast<Eigen::Index>(j - 1)) += weight / h0;
            }
        }
    }
    int operator()(const Eigen::VectorXd& x, Eigen::VectorXd& residuals) const {
        evaluate(x, residuals, nullptr);
        return 0;
    }
    int df(const Eigen::VectorXd& x, Eigen::MatrixXd& jacobian) const {
        Eigen::VectorXd residuals;
        evaluate(x, residuals, &jacobian);
        return 0;
    }
};

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
    BandData data;
    for (std::size_t first = 1; first <= top;) {
        const std::size_t width = std::max<std::size_t>(
            kProfileBandBins, static_cast<std::size_t>(std::ceil(kProfileBandWidth * static_cast<double>(first))));
        std::size_t last = std::min(top, first + width - 1);
        if (top - last < width / 2) last = top;  // no short band at the top
        double zeta = 0.0, psd = 0.0;
        for (std::size_t k = first; k <= last; ++k) zeta += static_cast<double>(k), psd += p.psd[k];
        const double bins = static_cast<double>(last - first + 1);
        if (psd > 0.0) {
            data.zeta.push_back(zeta / bins * dzeta_);
            data.psd.push_back(psd / bins);
            data.bins.push_back(bins);
            std::vector<double> samples;
            const std::size_t parts = std::min<std::size_t>(kBandSamples, last - first + 1);
            for (std::size_t i = 0; i < parts; ++i)
                samples.push_back((static_cast<double>(first) - 0.5 + (static_cast<double>(i) + 0.5) * bins / static_cast<double>(parts)) * dzeta_);
            data.samples.push_back(std::move(samples));
        }
        first = last + 1;
    }
    band_zeta_ = data.zeta, band_psd_ = data.psd;
    for (std::size_t bin : knot_bins(top)) log_knots_.push_back(std::log(static_cast<double>(bin) * dzeta_));
    if (data.zeta.size() < log_knots_.size() + 1)
        fail("{}: {} bands of its spectrum hold power; the fit of its 2-D PSD at {} knots needs at least {}", p.origin,
             data.zeta.size(), log_knots_.size(), log_knots_.size() + 1);
    // Start: at each knot the power law of the bands over the octave above it, P1 ~ u^-beta, read as the 2-D
    // P(z) = P1(z) / (z B(beta)) that a power law P ~ z^-(beta + 1) has (B as in KCorrelation::profile_psd_unit);
    // below the first knot where beta >= 1, that knot's value (a flat spectrum's P1 is no power law: read as one,
    // P would start far too high where the data constrain it least).
    const auto log_band_psd = [&](double s) {  // ln P1 linear in ln u between band centres, held beyond them
        std::size_t b = 0;
        while (b + 2 < data.zeta.size() && std::log(data.zeta[b + 1]) < s) ++b;
        const double s0 = std::log(data.zeta[b]), s1 = std::log(data.zeta[b + 1]);
        const double y0 = std::log(data.psd[b]), y1 = std::log(data.psd[b + 1]);
        return y0 + (y1 - y0) * std::clamp((s - s0) / (s1 - s0), 0.0, 1.0);
    };
    Eigen::VectorXd x(static_cast<Eigen::Index>(log_knots_.size()));
    std::size_t first_steep = log_knots_.size();
    for (std::size_t j = log_knots_.size(); j-- > 0;) {
        const double s = log_knots_[j], log_p1 = log_band_psd(s);
        const double beta = -(log_band_psd(s + std::log(2.0)) - log_p1) / std::log(2.0);
        if (beta >= 1.0) first_steep = j;
        const double b = std::clamp(beta, 1.0, 5.0);
        const double log_b = 0.5 * std::log(kPi) + std::lgamma(0.5 * b) - std::lgamma(0.5 * (b + 1.0));
        x[static_cast<Eigen::Index>(j)] = log_p1 - s - log_b;
    }
    for (std::size_t j = 0; j < first_steep && first_steep < log_knots_.size(); ++j)
        x[static_cast<Eigen::Index>(j)] = x[static_cast<Eigen::Index>(first_steep)];
    ProfileFitFunctor functor;
    functor.data = &data;
    functor.log_knots = &log_knots_;
    Eigen::LevenbergMarquardt<ProfileFitFunctor> solver(functor);
    solver.parameters.xtol = 1e-10;
    solver.parameters.ftol = 1e-12;
    solver.parameters.maxfev = 400;
    solver.minimize(x);
    if (!x.allFinite() || x.minCoeff() < std::log(std::numeric_limits<double>::min())) fail("{}: the fit of its 2-D PSD to its 1-D PSD did not converge", p.origin);
    log_psd_.assign(x.data(), x.data() + x.size());
    // P at the profile's bins, read as a map's ring means are (ring_psd.hpp), P(0) that below the first knot.
    std::vector<double> zeta, psd;
    for (std::size_t k = 1; k <= top; ++k) {
        zeta.push_back(static_cast<double>(k) * dzeta_);
        psd.push_back(fitted_psd(zeta.back()));
    }
    double p0 = std::exp(log_psd_.front());
    band_scale_ = rms_um_ * rms_um_ / std::pow(MapRingPsd(p0, zeta, psd, nyquist_, "unscaled").sigma_h(), 2);
    p0 *= band_scale_;
    for (double& v : psd) v *= band_scale_;
    std::string key = fmt::format("profile({:.17g};{:.17g};", nyquist_, p0);
    for (std::size_t i = 0; i < zeta.size(); ++i) key += fmt::format("{:.17g}:{:.17g};", zeta[i], psd[i]);
    psd_ = std::make_shared<const MapRingPsd>(p0, std::move(zeta), std::move(psd), nyquist_, key + ")");
}

double ProfileStatistics::fitted_psd(double z) const { return knot_psd(log_knots_, log_psd_, z, nullptr); }

double ProfileStatistics::fitted_profile_psd(double u) const { return abel_forward(log_knots_, log_psd_, u, nullptr); }

double ProfileStatistics::tail_power() const { return profile_tail_power(log_knots_, log_psd_); }

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
        "PSD, fitted: ln P piecewise linear in ln zeta at {} knots (constant below the first, {:.3g} rad/um, and "
        "continued beyond the last as zeta^-{:.3g}), whose Abel transform fits the 1-D PSD in {} bands ({} bins, "
        "widening to {:.0f} % of their frequency) by maximum likelihood, so that P >= 0 without clipping the noise; "
        "used over zeta {:.3g} .. {:.3g} rad/um (periods {:.3g} .. {:.3g} um) and rolled off as zeta^-200 beyond "
        "({:.2g} % of sigma^2); scaled by {:.4g} to carry the profile's variance: model sigma {:.6g} um, the "
        "profile's rms {:.6g} um (standard error of sigma {:.2g} %)",
        origin, kMeasuredIsotropyNote, s.knots(), s.first_ring(), s.tail_power(), s.band_zeta().size(),
        kProfileBandBins, 100 * kProfileBandWidth, s.first_ring(), s.nyquist(), kTwoPi / s.nyquist(),
        kTwoPi / s.first_ring(), 100.0 * s.above_band_fraction(), s.band_scale(), s.sigma_h(), s.map_rms(),
        100.0 * s.sigma_relative_error());
}

}  // namespace surfscatter::surface
