#pragma once
// A measured height map as radial PSD statistics for the scattering models: the ring means of the Hann-windowed
// periodogram (psd_estimate.hpp), merged into logarithmic bins, as a TabulatedPsd (radial_statistics.hpp), which
// interpolates log-log between the bins, stays flat below the first one and continues the last decade's power law
// beyond Nyquist. Binning reduces the periodogram's scatter (each ring alone scatters by 1/sqrt(nu), 10-40 %) to
// ~1/sqrt(sum of nu over the bin): a bin spans 1/bins_per_decade of a decade, and at low frequency, where rings
// hold few Fourier modes, as many rings as it takes to reach min_effective_samples (nu, see effective_samples();
// 100 -> ~10 % scatter). The price is resolution on the low-frequency plateau, which is flat for KC-like surfaces.
#include <cstddef>

#include "surfscatter/surface/height_map.hpp"
#include "surfscatter/surface/psd_estimate.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::surface {

struct PsdTableOptions {
    std::size_t min_ring = 2;           // lowest ring kept (ring 1 is smeared by the window's main lobe and tilt)
    double max_nyquist_fraction = 1.0;  // highest frequency kept, as a fraction of pi / max(dx, dy)
    double bins_per_decade = 20.0;
    double min_effective_samples = 100.0;
    Form form = Form::plane;            // removed before the PSD is estimated
};

// The log-binned samples (zeta strictly increasing, psd > 0) that tabulated_psd() passes to TabulatedPsd.
struct PsdSamples {
    std::vector<double> zeta, psd;
};
PsdSamples binned_psd_samples(const RadialPsd& radial, double nyquist_zeta, const PsdTableOptions& options = {});

// Error if fewer than kMinFitValidFraction of the map's points are valid.
TabulatedPsd tabulated_psd(const HeightMap& map, const PsdTableOptions& options = {});

}  // namespace surfscatter::surface
