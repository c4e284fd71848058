#pragma once
// A measured radial PSD given at nodes near multiples of one spacing (a map's ring means, map_statistics.hpp; a
// profile's isotropic 2-D PSD, profile_statistics.hpp): ln P linear in zeta between nodes, linear from P(0) to the
// first node, and beyond Nyquist rolled off as zeta^kRollOffPower from its value there.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

// Beyond Nyquist P falls as zeta^kRollOffPower from its value there: continuous (a sharp cut, sharp_cut.hpp, costs
// exact GHS eval 1.55x: its lobe table loses the log-valued fast path) and effectively zero within 2 % of Nyquist
// (0.02x at 1.02 zeta_N); it carries 2 pi P(zeta_N) zeta_N^2 / 198 of variance (above_band_fraction()).
inline constexpr double kRollOffPower = -200.0;

// The node values as a radial PSD, rolled off beyond Nyquist.
class MapRingPsd final : public NumericalRadialStatistics {
public:
    MapRingPsd(double dc, std::vector<double> zeta, std::vector<double> psd, double nyquist, std::string key)
        : zeta_(std::move(zeta)), log_psd_(psd.size()), nyquist_(nyquist), dc_(dc) {
        for (std::size_t i = 0; i < psd.size(); ++i) log_psd_[i] = std::log(psd[i]);
        first_ = psd[0];
        for (std::size_t i = 0; i + 1 < zeta_.size(); ++i)
            slope_.push_back((log_psd_[i + 1] - log_psd_[i]) / (zeta_[i + 1] - zeta_[i]));
        spacing_ = (zeta_.back() - zeta_.front()) / static_cast<double>(zeta_.size() - 1);
        edge_ = value_in_band(nyquist_);
        zeta_lo_ = zeta_[0] * 1e-4;
        zeta_hi_ = nyquist_;
        initialise(std::move(key));
    }

    // P (um^4) inside the band. Nodes sit near multiples of the spacing (skipped ones aside), so the segment is
    // found from a first guess and a few steps instead of a search (this is on the lobe's evaluation path).
    double value_in_band(double zeta) const {
        if (zeta <= zeta_.front()) return dc_ + (first_ - dc_) * zeta / zeta_.front();  // from P(0), the DC bin
        const std::size_t last = slope_.size() - 1;  // segments 0 .. last; beyond the last node: its segment continued
        std::size_t i = std::min(last, static_cast<std::size_t>((zeta - zeta_.front()) / spacing_));
        while (i > 0 && zeta_[i] > zeta) --i;
        while (i < last && zeta_[i + 1] <= zeta) ++i;
        return std::exp(log_psd_[i] + slope_[i] * (zeta - zeta_[i]));
    }

private:
    double psd_raw(double zeta) const override {
        return zeta <= nyquist_ ? value_in_band(zeta) : edge_ * std::pow(zeta / nyquist_, kRollOffPower);
    }

    std::vector<double> zeta_, log_psd_, slope_;
    double nyquist_, dc_, first_ = 0, edge_ = 0, spacing_ = 1;
};

}  // namespace surfscatter::surface
