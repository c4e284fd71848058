// Row alignment: no detection on synthesised KC and Gaussian maps (1 .. 64 pixels a correlation length), offsets of a
// tenth of the rms detected and recovered to within the surface's own row-mean profile, masks respected, a curvature
// across the rows left for form removal, and the names.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "height_test_util.hpp"
#include "row_profile.hpp"
#include "surfscatter/heightmap/rows.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::heightmap {
using surface::GaussianAcv;
using surface::KCorrelation;
using surface::synthesize_surface;
using test::error_of;
using test::minus_cubic;
using test::rms;
using test::row_means;
namespace {

std::vector<double> white(std::size_t n, double rms_um, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, rms_um);
    std::vector<double> v(n);
    for (double& x : v) x = normal(rng);
    return v;
}

HeightMap with_offsets(const HeightMap& map, const std::vector<double>& offsets) {
    std::vector<double> h = map.heights();
    for (std::size_t iy = 0; iy < map.ny(); ++iy)
        for (std::size_t ix = 0; ix < map.nx(); ++ix) h[iy * map.nx() + ix] += offsets[iy];
    return map.with_heights(std::move(h));
}

TEST(RowAlignment, NoDetectionOnSynthesisedMaps) {
    struct Case { double corr_length, gamma; };
    std::uint64_t seed = 11;
    double largest = 0;
    for (const Case c : {Case{0.25, 3.0}, Case{1.0, 2.2}, Case{2.5, 4.0}, Case{4.0, 6.0}, Case{16.0, 3.0}})
        for (int s = 0; s < 4; ++s) {
            const HeightMap map = synthesize_surface(KCorrelation(0.01, c.corr_length, c.gamma), {256, 256, 0.25}, seed++);
            const RowOffsets found = find_row_offsets(map);
            EXPECT_FALSE(found.detected) << c.corr_length << " " << c.gamma << ": " << found.reason;
            largest = std::max(largest, found.ratio);
        }
    for (int s = 0; s < 4; ++s) {
        const RowOffsets found = find_row_offsets(synthesize_surface(GaussianAcv(0.01, 3.0), {256, 192, 0.25}, seed++));
        EXPECT_FALSE(found.detected) << found.reason;
        largest = std::max(largest, found.ratio);
    }
    RecordProperty("largest_ratio", std::to_string(largest));
}

// Offsets of a tenth of the map's rms, white from row to row: detected, and the offsets found differ from the true
// ones (less their cubic) by no more than the surface's row-mean profile, which the method takes with them.
TEST(RowAlignment, AddedOffsetsAreDetectedAndRecovered) {
    for (const double corr_length : {0.5, 4.0}) {
        const HeightMap clean = synthesize_surface(KCorrelation(0.1, corr_length, 3.0), {256, 200, 0.25}, 21);
        const std::vector<double> truth = white(clean.ny(), 0.01, 5);
        RowOffsets found;
        const HeightMap aligned = align_rows(with_offsets(clean, truth), RowAlignment::automatic, found);
        EXPECT_TRUE(found.detected) << found.reason;
        RecordProperty("ratio_corr_length_" + std::to_string(int(corr_length * 10)), std::to_string(found.ratio));
        const std::vector<double> expected = minus_cubic(truth), profile = row_means(clean);
        std::vector<double> error(truth.size());
        for (std::size_t i = 0; i < truth.size(); ++i) error[i] = found.white_um[i] - expected[i];
        EXPECT_LT(rms(error), 1.5 * rms(profile) + 1e-4) << corr_length;
        EXPECT_NEAR(found.rms_um, rms(expected), 0.2 * rms(expected) + rms(profile));
        EXPECT_NEAR(found.white_rms_um, rms(expected), 0.2 * rms(expected) + rms(profile));
        // The aligned map is the clean one less what the method could not tell from offsets.
        for (std::size_t iy = 0; iy < clean.ny(); iy += 37)
            EXPECT_NEAR(aligned(17, iy) - clean(17, iy), expected[iy] - found.white_um[iy] + truth[iy] - expected[iy],
                        1e-12);
    }
}

TEST(RowAlignment, MasksAreRespected) {
    const HeightMap clean = synthesize_surface(KCorrelation(0.1, 1.0, 3.0), {200, 160, 0.25}, 31);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> uniform;
    std::vector<std::uint8_t> valid(clean.size(), 1);
    for (auto& v : valid) v = uniform(rng) > 0.15;
    for (std::size_t iy = 40; iy < 60; ++iy)
        for (std::size_t ix = 0; ix < 200; ++ix) valid[iy * 200 + ix] = ix >= 150;  // rows cut to their right quarter
    for (std::size_t ix = 0; ix < 200; ++ix) valid[100 * 200 + ix] = 0;             // a row with no valid point
    const HeightMap masked(200, 160, 0.25, 0.25, clean.heights(), valid, "masked");
    const std::vector<double> truth = white(160, 0.01, 9);
    RowOffsets found;
    const HeightMap aligned = align_rows(with_offsets(masked, truth), RowAlignment::automatic, found);
    EXPECT_TRUE(found.detected) << found.reason;
    EXPECT_EQ(found.unlinked_rows, 0u);
    EXPECT_EQ(found.offset_um[100], 0.0);
    EXPECT_EQ(found.white_um[100], 0.0);
    EXPECT_EQ(aligned.validity(), masked.validity());
    std::vector<double> t = truth, o = found.white_um;
    t.erase(t.begin() + 100), o.erase(o.begin() + 100);
    const std::vector<double> expected = minus_cubic(t);
    std::vector<double> profile = row_means(masked);
    profile.erase(profile.begin() + 100);
    double err = 0;
    for (std::size_t i = 0; i < t.size(); ++i) err += std::pow(o[i] - expected[i], 2);
    // Rows 40-59 hold a quarter of the points: their row means scatter twice as much, in the profile too.
    EXPECT_LT(std::sqrt(err / double(t.size())), 1.5 * rms(profile) + 1e-4) << found.reason;
    for (std::size_t i = 0; i < aligned.size(); ++i) {
        if (!aligned.valid(i)) {
            ASSERT_EQ(aligned.heights()[i], 0.0);
        }
    }
}

// A lay along the rows: a profile across them, constant along x, the map's own (a sinusoid of 16 rows and the cusps
// of a turned surface, feed 20 rows), both of peak-to-valley several times the roughness's rms.
std::vector<double> lay_profile(std::size_t ny, double amplitude_um) {
    std::vector<double> lay(ny);
    for (std::size_t iy = 0; iy < ny; ++iy) {
        const double t = std::fmod(double(iy) / 20.0, 1.0) - 0.5;
        lay[iy] = amplitude_um * (std::sin(2 * std::numbers::pi * double(iy) / 16.0 + 0.3) + 4.0 * t * t);
    }
    return lay;
}

// (b) A lay and no offsets: the rows' mean steps are significant (R), their white floor is not (W), so `auto` leaves
// the map exactly as it is; on KC maps of 1-16 pixels a correlation length.
TEST(RowAlignment, ALayAlongTheRowsIsNotTakenForOffsets) {
    std::uint64_t seed = 51;
    for (const double corr_length : {0.25, 1.0, 4.0})
        for (int s = 0; s < 2; ++s) {
            const HeightMap clean = synthesize_surface(KCorrelation(0.01, corr_length, 3.0), {256, 240, 0.25}, seed++);
            const HeightMap laid = with_offsets(clean, lay_profile(clean.ny(), 0.02));
            RowOffsets found;
            const HeightMap aligned = align_rows(laid, RowAlignment::automatic, found);
            EXPECT_TRUE(found.lay) << corr_length << ": " << found.reason;
            EXPECT_FALSE(found.detected) << corr_length << ": " << found.reason;
            EXPECT_EQ(aligned.heights(), laid.heights());
            RecordProperty("W_lay_" + std::to_string(seed), std::to_string(found.white_ratio));
        }
}

// (c) The lay (rms ~0.08 um) plus white offsets of 0.01 um on KC roughness of 0.05 um: detected; what `auto` removes
// is the offsets' white part, within 1.5 x the surface's row-mean profile plus 0.3 x the offsets' rms of the truth
// (the offsets in the spectral bins the lay holds stay: about sqrt(their share)), and the lay is kept: the aligned
// map's row means follow the map without offsets within the same bound (measured: 8 % of the lay's rms).
TEST(RowAlignment, OffsetsOnALayAreRemovedAndTheLayKept) {
    std::uint64_t seed = 61;
    for (const double corr_length : {0.5, 4.0}) {
        const HeightMap clean0 = synthesize_surface(KCorrelation(0.05, corr_length, 3.0), {256, 240, 0.25}, seed++);
        const std::vector<double> lay = lay_profile(clean0.ny(), 0.1);
        const HeightMap clean = with_offsets(clean0, lay);
        const std::vector<double> truth = white(clean.ny(), 0.01, seed++);
        RowOffsets found;
        const HeightMap aligned = align_rows(with_offsets(clean, truth), RowAlignment::automatic, found);
        ASSERT_TRUE(found.detected) << corr_length << ": " << found.reason;
        const std::vector<double> expected = minus_cubic(truth), profile = row_means(clean0);
        const std::vector<double> kept = row_means(aligned), wanted = row_means(clean);
        std::vector<double> error(truth.size()), lay_error(truth.size());
        for (std::size_t i = 0; i < truth.size(); ++i) {
            error[i] = found.white_um[i] - expected[i];
            lay_error[i] = kept[i] - wanted[i];
        }
        EXPECT_LT(rms(error), 1.5 * rms(profile) + 0.3 * rms(expected)) << corr_length << ": " << found.reason;
        EXPECT_LT(rms(lay_error), 1.5 * rms(profile) + 0.3 * rms(expected)) << corr_length;
        RecordProperty("offsets_error_" + std::to_string(seed), std::to_string(rms(error) / rms(expected)));
        RecordProperty("lay_error_" + std::to_string(seed), std::to_string(rms(lay_error) / rms(minus_cubic(lay))));
        // `median` takes the lay with the offsets: what auto keeps.
        RowOffsets all;
        align_rows(with_offsets(clean, truth), RowAlignment::median, all);
        EXPECT_GT(all.rms_um, 0.5 * rms(minus_cubic(lay)));
    }
}

// A curvature across the rows is form: not detected, and `median` leaves it in the map.
TEST(RowAlignment, CurvatureAcrossTheRowsIsLeftForFormRemoval) {
    const HeightMap clean = synthesize_surface(KCorrelation(0.01, 1.0, 3.0), {256, 256, 0.25}, 41);
    std::vector<double> h = clean.heights();
    for (std::size_t iy = 0; iy < 256; ++iy) {
        const double t = double(iy) / 255.0 * 2 - 1;
        for (std::size_t ix = 0; ix < 256; ++ix) h[iy * 256 + ix] += 0.5 * t * t + 0.2 * t * t * t;
    }
    const HeightMap curved = clean.with_heights(h);
    EXPECT_FALSE(find_row_offsets(curved).detected) << find_row_offsets(curved).reason;
    RowOffsets found;
    const HeightMap aligned = align_rows(curved, RowAlignment::median, found);
    EXPECT_LT(found.rms_um, 0.01);  // the surface's own row-mean profile, not the 0.5 um curvature
    EXPECT_NEAR(aligned(10, 0) - aligned(10, 128), curved(10, 0) - curved(10, 128), 0.01);
}

TEST(RowAlignment, NamesAndNone) {
    EXPECT_EQ(parse_row_alignment("auto", "--row-alignment"), RowAlignment::automatic);
    EXPECT_EQ(parse_row_alignment("median", "--row-alignment"), RowAlignment::median);
    EXPECT_EQ(parse_row_alignment("none", "--row-alignment"), RowAlignment::none);
    for (RowAlignment a : {RowAlignment::none, RowAlignment::median, RowAlignment::automatic})
        EXPECT_EQ(parse_row_alignment(to_string(a), "x"), a);
    EXPECT_EQ(error_of([] { parse_row_alignment("mean", "--row-alignment"); }),
              "--row-alignment must be one of none | median | auto, got 'mean'");
    const HeightMap map = synthesize_surface(KCorrelation(0.01, 1.0, 3.0), {64, 64, 0.25}, 1);
    RowOffsets found;
    found.rms_um = 5;
    EXPECT_EQ(align_rows(map, RowAlignment::none, found).heights(), map.heights());
    EXPECT_TRUE(found.offset_um.empty());
    EXPECT_EQ(found.rms_um, 0.0);
    EXPECT_EQ(align_rows(map, RowAlignment::automatic, found).heights(), map.heights());
    EXPECT_FALSE(found.detected);
    EXPECT_NE(describe(found, RowAlignment::automatic).find("not significant"), std::string::npos);
}

}  // namespace
}  // namespace surfscatter::heightmap
