#include "surfscatter/surface/map_statistics.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/sharp_cut.hpp"

namespace surfscatter::surface {
namespace {

constexpr double kTailPower = -8.0;  // P beyond Nyquist, which the cut removes: only its shape for the base's mass

// The ring means as a radial PSD over the whole plane (the base that the sharp cut at Nyquist keeps the disc of).
class RingPsd final : public NumericalRadialStatistics {
public:
    RingPsd(double dc, std::vector<double> zeta, std::vector<double> psd, double nyquist, std::string key)
        : zeta_(std::move(zeta)), log_psd_(psd.size()), nyquist_(nyquist), dc_(dc) {
        for (std::size_t i = 0; i < psd.size(); ++i) log_psd_[i] = std::log(psd[i]);
        first_ = psd[0];
        edge_ = value_in_band(nyquist_);
        zeta_lo_ = zeta_[0] * 1e-4;
        zeta_hi_ = nyquist_;
        initialise(std::move(key));
    }

private:
    double value_in_band(double zeta) const {
        if (zeta <= zeta_.front()) return dc_ + (first_ - dc_) * zeta / zeta_.front();  // from the periodogram's DC value
        const std::size_t n = zeta_.size();
        std::size_t i = static_cast<std::size_t>(std::upper_bound(zeta_.begin(), zeta_.end(), zeta) - zeta_.begin());
        i = std::min(std::max<std::size_t>(i, 1), n - 1);  // beyond the last ring: its last segment continued
        const double t = (zeta - zeta_[i - 1]) / (zeta_[i] - zeta_[i - 1]);
        return std::exp(log_psd_[i - 1] + t * (log_psd_[i] - log_psd_[i - 1]));
    }
    double psd_raw(double zeta) const override {
        return zeta <= nyquist_ ? value_in_band(zeta) : edge_ * std::pow(zeta / nyquist_, kTailPower);
    }

    std::vector<double> zeta_, log_psd_;
    double nyquist_, dc_, first_ = 0, edge_ = 0;
};

}  // namespace

double wrap_jump_ratio(const HeightMap& flat) {
    const std::size_t nx = flat.nx(), ny = flat.ny();
    double ratio = 0.0;
    for (int axis = 0; axis < 2; ++axis) {
        const std::size_t n = axis == 0 ? nx : ny, m = axis == 0 ? ny : nx;
        auto h = [&](std::size_t i, std::size_t j) { return axis == 0 ? flat(i, j) : flat(j, i); };
        double jump = 0.0, step = 0.0;
        for (std::size_t j = 0; j < m; ++j) {
            const double d = h(0, j) - h(n - 1, j);
            jump += d * d;
            for (std::size_t i = 0; i + 1 < n; ++i) {
                const double s = h(i + 1, j) - h(i, j);
                step += s * s;
            }
        }
        jump /= static_cast<double>(m);
        step /= static_cast<double>(m) * static_cast<double>(n - 1);
        ratio = std::max(ratio, step > 0.0 ? jump / step : (jump > 0.0 ? HUGE_VAL : 1.0));
    }
    return ratio;
}

MapStatistics::MapStatistics(const HeightMap& map, Form form) {
    require_valid_fraction(map, kMinFitValidFraction, "measured statistics");
    const HeightMap flat = remove_form(map, form);
    // Periodicity is the data's (its mean removed only): a form fitted to a periodic map is noise that would break it.
    periodic_ = !map.has_invalid() && wrap_jump_ratio(remove_form(map, Form::none)) <= kPeriodicJumpRatio;
    map_rms_ = rms_height(flat, Form::none);
    if (!(map_rms_ > 0.0))
        fail("{}: no roughness is left after removing the form ({}): rms height 0", map.origin(), to_string(form));
    spectrum_ = estimate_psd(flat, periodic_ ? Window::rectangular : Window::hann, Form::none);
    radial_ = radial_average(spectrum_);
    std::vector<double> zeta, psd;
    for (std::size_t i = 0; i < radial_.zeta.size(); ++i) {
        if (radial_.psd[i] > 0.0 && std::isfinite(radial_.psd[i])) {
            zeta.push_back(radial_.zeta[i]);
            psd.push_back(radial_.psd[i]);
        } else {
            ++skipped_rings_;
        }
    }
    if (zeta.size() < 4)
        fail("{}: only {} rings of its spectrum are positive; a measured PSD needs at least 4", map.origin(), zeta.size());
    const double nyquist = kPi / std::max(flat.spacing_x(), flat.spacing_y());
    // P(0): the periodogram's own DC value, 0 for the rectangular window (the mean is removed), with the Hann window
    // the power its main lobe moved there from the first rings.
    const double dc = std::max(0.0, spectrum_.values[0]);
    std::string key = fmt::format("map({};{};{:.17g};", periodic_ ? "rect" : "hann", nyquist, dc);
    for (std::size_t i = 0; i < zeta.size(); ++i) key += fmt::format("{:.17g}:{:.17g};", zeta[i], psd[i]);
    auto base = std::make_shared<RingPsd>(dc, std::move(zeta), std::move(psd), nyquist, key + ")");
    band_ = std::make_shared<SharpCutStatistics>(std::move(base), nyquist, CutPart::low_pass);
}

double MapStatistics::ring_samples(double zeta) const {
    const std::size_t ring = static_cast<std::size_t>(std::max(1.0, std::round(zeta / radial_.dzeta)));
    const std::size_t i = std::min(radial_.count.size(), ring) - 1;
    return effective_samples(radial_.window, radial_.count[i], radial_.valid_weight);
}

double MapStatistics::sigma_relative_error() const {
    double mass = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < radial_.psd.size(); ++i) {
        const double m = std::max(radial_.psd[i], 0.0) * radial_.count[i];
        mass += m;
        variance += m * m / effective_samples(radial_.window, radial_.count[i], radial_.valid_weight);
    }
    return mass > 0.0 ? 0.5 * std::sqrt(variance) / mass : 0.0;
}

}  // namespace surfscatter::surface
