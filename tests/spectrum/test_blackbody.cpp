// Planck's law against the check values of ../shared/data/constants.md (CODATA 2018, computed there by hand).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/physical_constants.hpp"

namespace ss = surfscatter::spectrum;

TEST(Blackbody, MatchesHandComputedCheckValues) {
    struct Case { double lambda, temperature, radiance; };
    const Case cases[] = {{500, 5000, 1.210719e4}, {560, 6504, 4.244787e4}, {555, 2856, 2.584769e2},
                          {1000, 1000, 6.720461e-2}};
    for (const auto& c : cases)
        EXPECT_NEAR(ss::blackbody_radiance(c.lambda, c.temperature) / c.radiance, 1.0, 1e-6)
            << c.lambda << " nm, " << c.temperature << " K";
}

TEST(Blackbody, PhotonEnergyConstant) { EXPECT_NEAR(ss::kPhotonEnergyNm, 1239.8419843320026, 1e-9); }

TEST(Blackbody, PeakFollowsWienAndIsAMaximum) {
    for (double t : {2700.0, 5000.0, 6504.0}) {
        const double peak = ss::blackbody_peak_wavelength_nm(t);
        EXPECT_NEAR(peak * t, 2.897771955e6, 1.0);
        EXPECT_GT(ss::blackbody_radiance(peak, t), ss::blackbody_radiance(peak * 0.99, t));
        EXPECT_GT(ss::blackbody_radiance(peak, t), ss::blackbody_radiance(peak * 1.01, t));
    }
}

TEST(Blackbody, ExtremeInputsStayFiniteOrThrow) {
    for (double lambda : {1e-3, 1.0, 380.0, 1e6, 1e12})
        for (double t : {1e-3, 1.0, 2700.0, 1e9}) {
            const double l = ss::blackbody_radiance(lambda, t);
            EXPECT_TRUE(std::isfinite(l) && l >= 0) << lambda << " " << t;
        }
    const double nan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(ss::blackbody_radiance(0, 2700), surfscatter::Error);
    EXPECT_THROW(ss::blackbody_radiance(500, -1), surfscatter::Error);
    EXPECT_THROW(ss::blackbody_radiance(nan, 2700), surfscatter::Error);
    EXPECT_THROW(ss::blackbody_radiance(500, nan), surfscatter::Error);
}
