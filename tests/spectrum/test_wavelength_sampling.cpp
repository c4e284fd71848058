#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfscatter/spectrum/wavelength_sampling.hpp"

using namespace surfscatter::spectrum;

TEST(WavelengthSampling, PdfIntegratesToOne) {
    // Piecewise constant: exact over the cells the inverse CDF delimits, and close on a fine uniform grid.
    double cells = 0;
    for (int k = 0; k < kVisibleCells; ++k) {
        const double lo = sample_visible_wavelength(static_cast<double>(k) / kVisibleCells);
        const double hi = sample_visible_wavelength(static_cast<double>(k + 1) / kVisibleCells);
        cells += visible_wavelength_pdf(0.5 * (lo + hi)) * (hi - lo);
    }
    EXPECT_NEAR(cells, 1.0, 1e-12);
    const int n = 47000;
    const double h = (kSampledLambdaMax - kSampledLambdaMin) / n;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += visible_wavelength_pdf(kSampledLambdaMin + (i + 0.5) * h) * h;
    EXPECT_NEAR(sum, 1.0, 1e-4);
    EXPECT_EQ(visible_wavelength_pdf(359.0), 0.0);
    EXPECT_EQ(visible_wavelength_pdf(831.0), 0.0);
}

TEST(WavelengthSampling, InverseCdfMatchesPdf) {
    // d lambda / du = 1 / p(lambda) inside every cell (finite differences that stay in the cell), and the end points
    // map to the range.
    EXPECT_NEAR(sample_visible_wavelength(0.0), kSampledLambdaMin, 1e-9);
    EXPECT_NEAR(sample_visible_wavelength(1.0), kSampledLambdaMax, 1e-9);
    for (int k = 0; k < kVisibleCells; ++k) {
        const double du = 0.25 / kVisibleCells;
        const double u = (k + 0.5) / kVisibleCells;
        const double slope = (sample_visible_wavelength(u + du) - sample_visible_wavelength(u - du)) / (2 * du);
        EXPECT_NEAR(slope * visible_wavelength_pdf(sample_visible_wavelength(u)), 1.0, 1e-9) << u;
        // The edges are the cells' own: the density just below an edge is the lower cell's.
        const double edge = sample_visible_wavelength(static_cast<double>(k) / kVisibleCells);
        if (k > 0) {
            EXPECT_EQ(visible_wavelength_pdf(edge), visible_wavelength_pdf(sample_visible_wavelength(u))) << k;
            EXPECT_EQ(visible_wavelength_pdf(std::nextafter(edge, 0.0)),
                      visible_wavelength_pdf(sample_visible_wavelength(u - 1.0 / kVisibleCells))) << k;
        }
    }
}

TEST(WavelengthSampling, CellsFollowTheSech2Density) {
    // The tabulated density against pbrt-v4's sech^2 one it approximates (the figures stated in the header).
    double worst_below_700 = 0, worst_below_780 = 0, worst = 0;
    for (double lambda = kSampledLambdaMin; lambda <= kSampledLambdaMax; lambda += 0.01) {
        const double deviation = std::abs(visible_wavelength_pdf(lambda) / visible_wavelength_sech2_pdf(lambda) - 1);
        worst = std::max(worst, deviation);
        if (lambda <= 700) worst_below_700 = std::max(worst_below_700, deviation);
        if (lambda <= 780) worst_below_780 = std::max(worst_below_780, deviation);
    }
    EXPECT_LT(worst_below_700, 0.012);
    EXPECT_LT(worst_below_780, 0.029);
    EXPECT_LT(worst, 0.059);
    EXPECT_GT(worst, 0.0);
    // The smooth density itself integrates to one.
    const int n = 47000;
    const double h = (kSampledLambdaMax - kSampledLambdaMin) / n;
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += visible_wavelength_sech2_pdf(kSampledLambdaMin + (i + 0.5) * h) * h;
    EXPECT_NEAR(sum, 1.0, 1e-8);
}

TEST(WavelengthSampling, ChiSquareOfEveryMember) {
    // Each of the four wavelengths must follow the visible density: 40 equal-probability bins, 40000 draws.
    const int bins = 40, draws = 40000;
    std::vector<double> edges(bins + 1);
    for (int b = 0; b <= bins; ++b) edges[b] = sample_visible_wavelength(static_cast<double>(b) / bins);
    for (int member = 0; member < kSpectrumSamples; ++member) {
        std::vector<int> counts(bins, 0);
        std::uint64_t state = 12345;
        for (int i = 0; i < draws; ++i) {
            state = state * 6364136223846793005ULL + 1442695040888963407ULL;
            const double u = static_cast<double>(state >> 11) * 0x1.0p-53;
            const double lambda = SampledWavelengths::sample_visible(u).lambda[member];
            int b = 0;
            while (b < bins - 1 && lambda > edges[b + 1]) ++b;
            ++counts[b];
        }
        double chi2 = 0;
        const double expected = static_cast<double>(draws) / bins;
        for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
        EXPECT_LT(chi2, 80.0) << "member " << member;  // 39 dof: p < 1e-4 threshold ~ 80
    }
}

TEST(WavelengthSampling, MembersAreStratifiedAndPdfsConsistent) {
    const SampledWavelengths w = SampledWavelengths::sample_visible(0.3);
    for (int i = 0; i < kSpectrumSamples; ++i) {
        EXPECT_GE(w.lambda[i], kSampledLambdaMin);
        EXPECT_LE(w.lambda[i], kSampledLambdaMax);
        EXPECT_DOUBLE_EQ(w.pdf[i], visible_wavelength_pdf(w.lambda[i]));
    }
    // u and u + 1/4 give the same set, rotated.
    const SampledWavelengths r = SampledWavelengths::sample_visible(0.55);
    EXPECT_NEAR(r.lambda[3], w.lambda[0], 1e-9);
    EXPECT_NEAR(r.lambda[0], w.lambda[1], 1e-9);
    const SampledWavelengths uni = SampledWavelengths::sample_uniform(0.0);
    EXPECT_DOUBLE_EQ(uni.lambda[1], kSampledLambdaMin + 470.0 / 4);
    EXPECT_DOUBLE_EQ(uni.pdf[2], 1.0 / 470.0);
}
