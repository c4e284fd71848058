#include "surfscatter/surface/map_statistics.hpp"

#include "surfscatter/surface/ring_psd.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"

namespace surfscatter::surface {
double lowest_ring_mean(const Psd2d& p) {
    if (p.nx < 3 || p.ny < 3) fail("a measured spectrum needs at least 3 x 3 bins, got {} x {}", p.nx, p.ny);
    const std::size_t hx = p.half_nx(), last = p.ny - 1;
    // The 8 bins around DC in the full plane: (+-1, 0), (0, +-1), (+-1, +-1); (-kx, -ky) mirrors (kx, ky).
    const double sum = 2 * p.values[1] + p.values[hx] + p.values[last * hx] + 2 * p.values[hx + 1] +
                       2 * p.values[last * hx + 1];
    return std::max(0.0, sum / 8);
}

MapStatistics::MapStatistics(const heightmap::HeightMap& map, heightmap::Form form) {
    heightmap::require_valid_fraction(map, heightmap::kMinFitValidFraction, "measured statistics");
    const heightmap::HeightMap flat = heightmap::remove_form(map, form);
    periodic_ = heightmap::is_periodic(map);
    map_rms_ = heightmap::rms_height(flat, heightmap::Form::none);
    if (!(map_rms_ > 0.0))
        fail("{}: no roughness is left after removing the form ({}): rms height 0", map.origin(), to_string(form));
    spectrum_ = estimate_psd(flat, periodic_ ? Window::rectangular : Window::hann, heightmap::Form::none);
    // Window correction: the Hann periodogram carries the window-weighted variance, which weighs the map's centre;
    // scaled to the map's own variance (every point alike), its shape stays the centre's and its level is the whole
    // map's (1 to round-off for the rectangular window of a periodic map).
    const double weighted = spectrum_.integral();
    if (!(weighted > 0.0)) fail("{}: its periodogram holds no power", map.origin());
    window_scale_ = map_rms_ * map_rms_ / weighted;
    for (double& v : spectrum_.values) v *= window_scale_;
    radial_ = radial_average(spectrum_);
    // P(0): the DC bin is not the surface's power at zero frequency but what removing the mean left there (0 with the
    // rectangular window; with the Hann window the power its main lobe moved there from the first rings), which put a
    // hole in the lobe's core exactly at specular (SSA ~1e-25 there, GHS 3-6x low at small g). It is continued from
    // the lattice's lowest ring instead, the mean of its 8 neighbours, in the 2-D spectrum that the 2-D route reads
    // and as the ring route's P(0), so that the core follows the lowest rings continuously (docs/HEIGHTMAPS.md).
    spectrum_.values[0] = lowest_ring_mean(spectrum_);
    double dc = spectrum_.values[0];
    // The rings used and the lattice's sum over them and DC (each ring's mean times its points): what the map holds
    // in the band (Parseval).
    std::vector<double> zeta, psd;
    double lattice_sum = dc;
    for (std::size_t i = 0; i < radial_.zeta.size(); ++i) {
        if (radial_.psd[i] > 0.0 && std::isfinite(radial_.psd[i])) {
            zeta.push_back(radial_.zeta[i]);
            psd.push_back(radial_.psd[i]);
            lattice_sum += radial_.psd[i] * radial_.count[i];
        } else {
            ++skipped_rings_;
        }
    }
    lattice_sum *= spectrum_.dzeta_x * spectrum_.dzeta_y;
    if (zeta.size() < 4)
        fail("{}: only {} rings of its spectrum are positive; a measured PSD needs at least 4", map.origin(), zeta.size());
    const double nyquist = kPi / std::max(flat.spacing_x(), flat.spacing_y());
    // The continuous reading of the ring means integrates over the band to a little less or more than the lattice's
    // sum (the lowest rings hold more lattice points than their annuli's area: -0.3 to -1 % measured), which would put
    // sigma_rel, and with it the scattered fraction 1 - e^{-g0}, off by as much: the ring means are scaled by the one
    // factor that makes the two equal (band_scale()).
    const auto in_band = [&](const MapRingPsd& p) { return p.sigma_h() * p.sigma_h() * p.radial_cdf(nyquist); };
    band_scale_ = lattice_sum / in_band(MapRingPsd(dc, zeta, psd, nyquist, "unscaled"));
    dc *= band_scale_;
    for (double& p : psd) p *= band_scale_;
    std::string key = fmt::format("map({};{};{:.17g};", periodic_ ? "rect" : "hann", nyquist, dc);
    for (std::size_t i = 0; i < zeta.size(); ++i) key += fmt::format("{:.17g}:{:.17g};", zeta[i], psd[i]);
    rings_psd_ = std::make_shared<MapRingPsd>(dc, std::move(zeta), std::move(psd), nyquist, key + ")");
    inverse_variance_ = 1.0 / (rings_psd_->sigma_h() * rings_psd_->sigma_h());
    nyquist_ = nyquist;
}

// The ring PSD answers for the statistics; psd_unit reads it without the virtual call.
double MapStatistics::sigma_h() const { return rings_psd_->sigma_h(); }
double MapStatistics::acv_normalized(double r) const { return rings_psd_->acv_normalized(r); }
double MapStatistics::radial_cdf(double zeta) const { return rings_psd_->radial_cdf(zeta); }
double MapStatistics::correlation_length() const { return rings_psd_->correlation_length(); }
std::string MapStatistics::cache_key() const { return rings_psd_->cache_key(); }

double MapStatistics::psd_unit(double zeta) const {
    // = rings_psd_->psd_unit(zeta) inside the band, without its virtual call (this is on the lobe's evaluation path).
    if (zeta >= 0.0 && zeta <= nyquist_) return rings_psd_->value_in_band(zeta) * inverse_variance_;
    return rings_psd_->psd_unit(zeta);
}

double MapStatistics::ring_samples(double zeta) const {
    const std::size_t ring = static_cast<std::size_t>(std::max(1.0, std::round(zeta / radial_.dzeta)));
    const std::size_t i = std::min(radial_.count.size(), ring) - 1;
    return effective_samples(radial_.window, radial_.count[i], radial_.valid_weight);
}

double MapStatistics::sigma_relative_error() const {
    // The window correction scales the periodogram's total to the map's own variance, the unweighted mean of h^2,
    // whose scatter is that of the rectangular periodogram's sum: independent bins whatever the window, not the Hann
    // window's correlated neighbours (35/18 per axis; with them the error came out 1.24-1.51x the scatter over
    // realisations, MapStatistics.SigmaStandardErrorMatchesTheScatterOverRealisations).
    double mass = 0.0, variance = 0.0;
    for (std::size_t i = 0; i < radial_.psd.size(); ++i) {
        const double m = std::max(radial_.psd[i], 0.0) * radial_.count[i];
        mass += m;
        variance += m * m / effective_samples(Window::rectangular, radial_.count[i], radial_.valid_weight);
    }
    return mass > 0.0 ? 0.5 * std::sqrt(variance) / mass : 0.0;
}

}  // namespace surfscatter::surface
