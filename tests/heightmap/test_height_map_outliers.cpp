// find_outliers / fill_outliers: no false alarm on Gaussian maps, spikes put on a map found exactly and filled close
// to the heights they hid, invalid points left alone, and the policy's names.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/outliers.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::heightmap {
using surface::synthesize_surface;
using surface::KCorrelation;
using surface::GaussianAcv;
namespace {

HeightMap kc_map(std::size_t n, std::uint64_t seed) {
    return synthesize_surface(KCorrelation(0.01, 1.0, 3.0), {n, n, 0.25}, seed);
}

// Rough and smooth at the pixel scale (2 .. 50 pixels a correlation length, gamma 2.2 .. 6, and a Gaussian ACV): the
// slope-free residuals keep the edges and the smooth maps' curvature from raising false alarms (a plain 5 x 5 median
// residual flagged thousands of points on the smoothest of these).
TEST(HeightMapOutliers, NoneOnGaussianMaps) {
    struct Case { double corr_length, gamma; };
    std::uint64_t seed = 1;
    for (const Case c : {Case{0.5, 3.0}, Case{4.0, 2.2}, Case{12.5, 6.0}}) {
        const HeightMap map = synthesize_surface(KCorrelation(0.01, c.corr_length, c.gamma), {512, 512, 0.25}, seed++);
        const Outliers o = find_outliers(map);
        EXPECT_EQ(o.count, 0u) << c.corr_length << " " << c.gamma << ": " << describe(o);
        EXPECT_TRUE(o.mask.empty());
        EXPECT_GT(o.robust_sigma_um, 0.0);
    }
    EXPECT_EQ(find_outliers(synthesize_surface(GaussianAcv(0.01, 12.5), {512, 512, 0.25}, seed)).count, 0u);
}

TEST(HeightMapOutliers, SpikesAreFoundExactlyAndFilledFromTheirNeighbours) {
    const HeightMap clean = kc_map(256, 3);
    const double s = find_outliers(clean).robust_sigma_um;
    std::vector<double> h = clean.heights();
    std::set<std::size_t> spikes;
    const std::size_t n = clean.nx();
    // 30 single points of +-(30 .. 350) s, one 2 x 2 spot, one on the left and one on the bottom edge.
    for (std::size_t k = 0; k < 30; ++k) spikes.insert((17 + 7 * k) * n + (11 + 8 * k));
    for (std::size_t p : {100 * n + 200, 100 * n + 201, 101 * n + 200, 101 * n + 201, 5 * n, n * n - n / 2}) spikes.insert(p);
    std::size_t k = 0;
    for (std::size_t p : spikes) {
        h[p] += (k % 2 ? 1.0 : -1.0) * s * (30.0 + 9.0 * double(k));
        ++k;
    }
    const HeightMap spiked = clean.with_heights(h);
    const Outliers o = find_outliers(spiked);
    ASSERT_EQ(o.count, spikes.size()) << describe(o);
    for (std::size_t p : spikes) EXPECT_EQ(o.mask[p], 1) << p;
    EXPECT_EQ(o.spots, spikes.size() - 3);  // the 2 x 2 spot is one
    EXPECT_TRUE(o.dominant()) << describe(o);
    const HeightMap filled = fill_outliers(spiked, o);
    double worst = 0;
    for (std::size_t i = 0; i < h.size(); ++i) {
        if (spikes.count(i)) {
            worst = std::max(worst, std::abs(filled.heights()[i] - clean.heights()[i]) / s);
        } else {
            EXPECT_EQ(filled.heights()[i], spiked.heights()[i]) << i;
        }
    }
    std::printf("filled spikes against the heights they hid: within %.3g robust sigma\n", worst);
    EXPECT_LT(worst, 4.0);
    EXPECT_EQ(find_outliers(filled).count, 0u);
    // A corner has no pair of points symmetric about it, the points next to it too few: not tested.
    std::vector<double> corner = clean.heights();
    corner.back() += 300 * s;
    EXPECT_EQ(find_outliers(clean.with_heights(corner)).count, 0u);
}

TEST(HeightMapOutliers, InvalidPointsStayInvalidAndAreNeverFlagged) {
    const HeightMap clean = kc_map(128, 4);
    std::vector<double> h = clean.heights();
    std::vector<std::uint8_t> valid(h.size(), 1);
    for (std::size_t i = 0; i < 40 * 128; ++i) valid[i] = 0;  // the first 40 rows
    h[60 * 128 + 64] += 1.0;                                   // a spike of 100 sigma
    h[41 * 128 + 3] -= 1.0;                                    // one next to the invalid rows
    const HeightMap map(128, 128, 0.25, 0.25, h, valid, "test map");
    const Outliers o = find_outliers(map);
    ASSERT_EQ(o.count, 2u) << describe(o);
    EXPECT_EQ(o.mask[60 * 128 + 64], 1);
    EXPECT_EQ(o.mask[41 * 128 + 3], 1);
    const HeightMap filled = fill_outliers(map, o);
    EXPECT_EQ(filled.valid_count(), map.valid_count());
    EXPECT_LT(std::abs(filled.heights()[60 * 128 + 64] - clean.heights()[60 * 128 + 64]), 0.05);
}

TEST(HeightMapOutliers, PolicyNames) {
    EXPECT_EQ(parse_outlier_policy("keep", "--outliers"), OutlierPolicy::keep);
    EXPECT_EQ(parse_outlier_policy("fill", "--outliers"), OutlierPolicy::fill);
    EXPECT_EQ(to_string(OutlierPolicy::fill), "fill");
    try {
        parse_outlier_policy("remove", "--outliers");
        FAIL() << "accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("'remove'"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace surfscatter::heightmap
