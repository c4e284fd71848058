#include "surfscatter/surface/psd_estimate_table.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/kc_fit.hpp"

namespace surfscatter::surface {

PsdSamples binned_psd_samples(const RadialPsd& radial, double nyquist, const PsdTableOptions& options) {
    if (options.min_ring < 1) fail("PSD table: the first ring must be >= 1, got {}", options.min_ring);
    if (!(options.max_nyquist_fraction > 0.0 && options.max_nyquist_fraction <= 1.0))
        fail("PSD table: the upper limit must be a fraction of Nyquist in (0, 1], got {}",
             options.max_nyquist_fraction);
    if (!(options.bins_per_decade > 0.0 && std::isfinite(options.bins_per_decade)))
        fail("PSD table: bins per decade must be positive, got {}", options.bins_per_decade);
    if (!(options.min_effective_samples >= 0.0 && std::isfinite(options.min_effective_samples)))
        fail("PSD table: minimum samples per bin must be >= 0, got {}", options.min_effective_samples);
    const double zeta_min = (static_cast<double>(options.min_ring) - 0.5) * radial.dzeta;
    const double zeta_max = options.max_nyquist_fraction * nyquist;

    PsdSamples samples;
    long current_bin = -1;
    double sum_count = 0.0, sum_zeta = 0.0, sum_psd = 0.0, sum_nu = 0.0;
    auto flush = [&] {
        if (sum_count > 0.0 && sum_psd > 0.0) {
            samples.zeta.push_back(sum_zeta / sum_count);
            samples.psd.push_back(sum_psd / sum_count);
        }
        sum_count = sum_zeta = sum_psd = sum_nu = 0.0;
    };
    for (std::size_t i = 0; i < radial.zeta.size(); ++i) {
        if (radial.zeta[i] < zeta_min || radial.zeta[i] > zeta_max) continue;
        const auto bin = static_cast<long>(std::floor(options.bins_per_decade * std::log10(radial.zeta[i] / zeta_min)));
        if (bin != current_bin && sum_nu >= options.min_effective_samples) flush();
        current_bin = bin;
        sum_nu += effective_samples(radial.window, radial.count[i], radial.valid_weight);
        sum_count += radial.count[i];
        sum_zeta += radial.count[i] * radial.zeta[i];
        sum_psd += radial.count[i] * radial.psd[i];
    }
    flush();
    if (samples.zeta.size() < 4)
        fail("PSD table: only {} PSD samples between {} and {} rad/um; the map is too small", samples.zeta.size(),
             zeta_min, zeta_max);
    return samples;
}

TabulatedPsd tabulated_psd(const HeightMap& map, const PsdTableOptions& options) {
    require_valid_fraction(map, kMinFitValidFraction, "a tabulated PSD");
    PsdSamples samples = binned_psd_samples(radial_average(estimate_psd(map, Window::hann, options.form)),
                                            nyquist_zeta(map), options);
    return TabulatedPsd(std::move(samples.zeta), std::move(samples.psd));
}

}  // namespace surfscatter::surface
