// Spectral synthesis: determinism, and the estimated PSD of a synthetic surface against the closed form it was
// made from.
#include <gtest/gtest.h>

#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/psd_estimate.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter::surface;

TEST(HeightSynthesis, SameSeedSameSurface) {
    const ss::KCorrelation kc(0.2, 3.0, 2.5);
    const ss::HeightMap a = ss::synthesize_surface(kc, {64, 48, 0.5}, 42);
    const ss::HeightMap b = ss::synthesize_surface(kc, {64, 48, 0.5}, 42);
    const ss::HeightMap c = ss::synthesize_surface(kc, {64, 48, 0.5}, 43);
    EXPECT_EQ(a.heights(), b.heights());
    EXPECT_NE(a.heights(), c.heights());
    EXPECT_EQ(a.nx(), 64u);
    EXPECT_EQ(a.ny(), 48u);
    EXPECT_DOUBLE_EQ(a.spacing_x(), 0.5);
}

TEST(HeightSynthesis, RejectsBadGrids) {
    const ss::KCorrelation kc(0.2, 3.0, 2.5);
    EXPECT_THROW(ss::synthesize_surface(kc, {7, 64, 0.5}, 1), surfscatter::Error);
    EXPECT_THROW(ss::synthesize_surface(kc, {64, 64, 0.0}, 1), surfscatter::Error);
    EXPECT_THROW(ss::synthesize_surface(kc, {64, 64, -2.0}, 1), surfscatter::Error);
}

// The ring means of the Hann periodogram of a synthetic KC surface follow the KC PSD. Statistics: ln of a ring
// mean has variance 1/nu and mean -1/(2 nu) (effective_samples), so over a group of rings the nu-weighted mean
// of ln(ring / model) + 1/(2 nu) is 0 with standard deviation 1/sqrt(sum nu). Allowed: 4 standard deviations
// plus 1 % for the window's smoothing of the curved PSD.
TEST(HeightSynthesis, RadialPsdMatchesKcInResolvedBand) {
    for (double gamma : {2.0, 3.0, 4.0}) {
        const ss::KCorrelation kc(0.1, 2.0, gamma);  // L = 4 pixels of 0.5 um
        const ss::HeightMap map = ss::synthesize_surface(kc, {512, 512, 0.5}, 7);
        const ss::RadialPsd radial = ss::radial_average(ss::estimate_psd(map));
        // Groups of rings [4, 8), [8, 16), ..., [128, 256): plateau, knee and tail (zeta L from 0.2 to 6).
        for (std::size_t first = 4; first < 256; first *= 2) {
            double sum_nu = 0.0, sum = 0.0;
            for (std::size_t ring = first; ring < 2 * first; ++ring) {
                const std::size_t i = ring - 1;
                const double nu = ss::effective_samples(radial.window, radial.count[i]);
                sum += nu * (std::log(radial.psd[i] / kc.psd(radial.zeta[i])) + 0.5 / nu);
                sum_nu += nu;
            }
            EXPECT_LT(std::abs(sum / sum_nu), 4.0 / std::sqrt(sum_nu) + 0.01)
                << "gamma " << gamma << ", rings " << first << ".." << 2 * first - 1;
        }
    }
}
