#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "synthetic.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/color_checker.hpp"

namespace surfscatter::photo {
namespace {

const ChartReference& reference() {
    static const ChartReference ref = read_chart_reference();
    return ref;
}

// The reference patches in linear sRGB, clipped into the gamut a real chart photo can hold.
std::array<Vec3d, kChartPatches> reference_patches() {
    std::array<Vec3d, kChartPatches> p = reference().linear_srgb;
    for (auto& v : p)
        for (auto& c : v) c = std::clamp(c, 0.0, 1.0);
    return p;
}

// A camera-like colour cast and exposure: measured = 0.7 * C * true.
const cv::Matx33d kCast(1.10, 0.12, -0.02,  //
                        0.05, 0.85, 0.10,   //
                        -0.03, 0.08, 0.62);

std::array<Vec3d, kChartPatches> cast(const std::array<Vec3d, kChartPatches>& in) {
    std::array<Vec3d, kChartPatches> out;
    for (std::size_t i = 0; i < in.size(); ++i) {
        const cv::Vec3d v = 0.7 * (kCast * cv::Vec3d(in[i][0], in[i][1], in[i][2]));
        out[i] = {v[0], v[1], v[2]};
    }
    return out;
}

TEST(ChartReference, ArgyllValuesAreTheColorChecker) {
    const auto& ref = reference();
    EXPECT_NEAR(ref.lab_d50[0].L, 37.99, 1e-9);   // dark skin
    EXPECT_NEAR(ref.lab_d50[18].L, 96.55, 0.5);   // white 9.5
    // White and the neutral row come out nearly neutral in linear sRGB after Bradford adaptation to D65.
    for (int i = 18; i < 24; ++i) {
        const auto& v = ref.linear_srgb[static_cast<std::size_t>(i)];
        EXPECT_NEAR(v[0] / v[1], 1.0, 0.05) << "patch " << i + 1;
        EXPECT_NEAR(v[2] / v[1], 1.0, 0.06) << "patch " << i + 1;
    }
    EXPECT_NEAR(ref.linear_srgb[18][1], 0.9, 0.03);
}

TEST(ChartReference, MissingFileIsReported) {
    EXPECT_THROW(read_chart_reference("/nonexistent/chart.cie"), Error);
}

TEST(ColorCorrection, KnownCastIsRemovedFromGivenCorners) {
    const std::array<cv::Point2f, 4> corners{cv::Point2f{210, 160}, {1010, 190}, {990, 720}, {230, 700}};
    const cv::Mat photo = synthetic::chart_photo(cast(reference_patches()), {1280, 960}, corners);
    const auto measured = sample_patches(photo, corners);
    const DeltaEStats before = chart_delta_e(measured, reference());
    for (const CcmConstraint constraint : {CcmConstraint::None, CcmConstraint::PreserveWhite}) {
        const cv::Matx33d ccm = fit_ccm(measured, reference(), constraint);
        const auto corrected = apply_ccm(measured, ccm);
        const DeltaEStats after = chart_delta_e(corrected, reference());
        std::printf("[ measured ] CCM (%s): mean dE00 %.3f -> %.3f, max %.3f -> %.3f\n",
                    constraint == CcmConstraint::None ? "least squares" : "white-preserving", before.mean,
                    after.mean, before.max, after.max);
        EXPECT_GT(before.mean, 5.0);
        EXPECT_LT(after.mean, 2.0);
        // The inverse cast (up to the exposure) is what the fit must find.
        const cv::Matx33d product = ccm * kCast * 0.7;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(product(r, c), r == c ? 1.0 : 0.0, 0.08);
        if (constraint == CcmConstraint::PreserveWhite) {
            for (std::size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(corrected[kWhitePatch][c], reference().linear_srgb[kWhitePatch][c], 1e-9);
        }
    }
}

// A camera a 3x3 matrix cannot fully undo: the cast, then a mildly non-linear response per channel.
std::array<Vec3d, kChartPatches> nonlinear_camera(const std::array<Vec3d, kChartPatches>& in) {
    auto out = cast(in);
    for (auto& v : out)
        for (auto& c : v) c = std::pow(std::max(c, 0.0), 0.85);
    return out;
}

TEST(ColorCorrection, Ciede2000FitLowersTheMeanErrorTheLeastSquaresFitLeaves) {
    const auto measured = nonlinear_camera(reference_patches());
    for (const CcmConstraint constraint : {CcmConstraint::None, CcmConstraint::PreserveWhite}) {
        const auto least_squares = apply_ccm(measured, fit_ccm(measured, reference(), constraint));
        const auto ciede = apply_ccm(measured, fit_ccm(measured, reference(), constraint, CcmObjective::Ciede2000));
        const double ls = chart_delta_e(least_squares, reference()).mean;
        const double de = chart_delta_e(ciede, reference()).mean;
        std::printf("[ measured ] non-linear camera (%s): mean dE00 least squares %.3f, CIEDE2000 fit %.3f\n",
                    constraint == CcmConstraint::None ? "free" : "white preserved", ls, de);
        EXPECT_GT(ls, 1.0);
        // Preserving the white leaves the fit 6 of its 9 degrees of freedom, and less to gain.
        EXPECT_LT(de, (constraint == CcmConstraint::None ? 0.8 : 0.95) * ls);
        if (constraint == CcmConstraint::PreserveWhite) {
            for (std::size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(ciede[kWhitePatch][c], reference().linear_srgb[kWhitePatch][c], 1e-9);
        }
    }
    // On a purely linear cast the least-squares fit is the exact inverse (the error left is the reference's clipping
    // into the gamut) and the CIEDE2000 fit does not make it worse.
    const auto linear = cast(reference_patches());
    const double exact = chart_delta_e(apply_ccm(linear, fit_ccm(linear, reference(), CcmConstraint::None)),
                                       reference()).mean;
    EXPECT_LE(chart_delta_e(apply_ccm(linear, fit_ccm(linear, reference(), CcmConstraint::None,
                                                      CcmObjective::Ciede2000)),
                            reference()).mean,
              exact + 1e-12);
    EXPECT_EQ(ccm_objective_by_name("least-squares"), CcmObjective::LeastSquares);
    EXPECT_THROW(ccm_objective_by_name("l2"), Error);
}

TEST(ColorCorrection, FlatFieldUndoesUnevenLighting) {
    // Light falling off across the chart by up to 35 %, tinted (the lamp's and a coloured bounce).
    const auto even = cast(reference_patches());
    std::array<Vec3d, kChartPatches> uneven, flat;
    for (std::size_t i = 0; i < even.size(); ++i) {
        const double column = static_cast<double>(i % 6), row = static_cast<double>(i / 6);
        const Vec3d light{1.0 - 0.05 * column - 0.04 * row, 1.0 - 0.06 * column - 0.03 * row, 0.95 - 0.05 * column};
        for (std::size_t c = 0; c < 3; ++c) {
            uneven[i][c] = even[i][c] * light[c];
            flat[i][c] = 0.18 * 0.7 * light[c];
        }
    }
    const auto evened = flatten_patches(uneven, flat);
    // The flat field restores the even chart up to one gain per channel, which the matrix absorbs.
    for (std::size_t i = 0; i < even.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            EXPECT_NEAR(evened[i][c] / even[i][c], evened[0][c] / even[0][c], 1e-12) << "patch " << i + 1;
    const double without = chart_delta_e(apply_ccm(uneven, fit_ccm(uneven, reference(), CcmConstraint::None)),
                                         reference()).mean;
    const double with = chart_delta_e(apply_ccm(evened, fit_ccm(evened, reference(), CcmConstraint::None)),
                                      reference()).mean;
    const double evenly_lit = chart_delta_e(apply_ccm(even, fit_ccm(even, reference(), CcmConstraint::None)),
                                            reference()).mean;
    std::printf("[ measured ] uneven lighting: mean dE00 %.3f without the flat field, %.3f with it (evenly lit: %.3f)\n",
                without, with, evenly_lit);
    EXPECT_GT(without, 2.0);
    EXPECT_NEAR(with, evenly_lit, 1e-9);
    flat[7][1] = 0.0;
    try {
        flatten_patches(uneven, flat);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("patch 8"), std::string::npos) << e.what();
    }
}

TEST(ColorCorrection, ApplyCcmMultipliesEveryPixel) {
    cv::Mat image(2, 2, CV_32FC3, cv::Scalar(0.2, 0.4, 0.6));
    const cv::Matx33d m(1, 0, 0, 0, 2, 0, 0.5, 0, 1);
    const cv::Mat out = apply_ccm(image, m);
    const cv::Vec3f v = out.at<cv::Vec3f>(1, 1);
    EXPECT_NEAR(v[0], 0.2, 1e-6);
    EXPECT_NEAR(v[1], 0.8, 1e-6);
    EXPECT_NEAR(v[2], 0.7, 1e-6);
}

TEST(ColorCorrection, MccFindsTheChartAndItsOrientation) {
    for (const double angle_deg : {0.0, 12.0, 180.0 + 8.0, -90.0 + 5.0}) {
        const cv::Point2f centre(640, 480);
        const double a = angle_deg * M_PI / 180.0;
        const auto rot = [&](float x, float y) {
            return centre + cv::Point2f(float(x * std::cos(a) - y * std::sin(a)), float(x * std::sin(a) + y * std::cos(a)));
        };
        const std::array<cv::Point2f, 4> corners{rot(-330, -220), rot(330, -220), rot(330, 220), rot(-330, 220)};
        const cv::Mat photo = synthetic::chart_photo(cast(reference_patches()), {1280, 960}, corners);
        const auto found = detect_chart(photo, reference());
        const auto expected = sample_patches(photo, corners);
        const auto got = sample_patches(photo, found);
        for (std::size_t i = 0; i < expected.size(); ++i)
            for (std::size_t c = 0; c < 3; ++c)
                EXPECT_NEAR(got[i][c], expected[i][c], 0.01) << "angle " << angle_deg << " patch " << i + 1;
    }
}

TEST(ColorCorrection, NoChartIsReported) {
    const cv::Mat blank(480, 640, CV_32FC3, cv::Scalar::all(0.3));
    EXPECT_THROW(detect_chart(blank, reference()), Error);
}

}  // namespace
}  // namespace surfscatter::photo
