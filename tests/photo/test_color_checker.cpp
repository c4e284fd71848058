#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/mcc/ccm.hpp>

#include "synthetic.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/spectrum/color.hpp"

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

// ---- 8-bit photographs of the chart as cameras write them: a cast in light, then a tone curve, 8-bit codes, JPEG.

// The camera's tone curve from linear light to codes.
enum class Encoder { Srgb, Gamma22, SCurve };
const char* name(Encoder e) { return e == Encoder::Srgb ? "sRGB" : e == Encoder::Gamma22 ? "gamma 2.2" : "S-curve"; }
double encode(Encoder e, double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    switch (e) {
        case Encoder::Srgb: return spectrum::srgb_encode(linear);
        case Encoder::Gamma22: return std::pow(linear, 1 / 2.2);
        case Encoder::SCurve: {
            // A contrast S-curve on top of gamma 2.2, as consumer cameras render: toe and shoulder compressed.
            const double y = std::pow(linear, 1 / 2.2), k = 2.5;
            return 0.5 + 0.5 * std::tanh(k * (y - 0.5)) / std::tanh(0.5 * k);
        }
    }
    return linear;
}

// The chart under the cast, encoded by `e`, with sensor noise, a specular glint on the white patch and a dust speck on
// the red patch, written as a JPEG (quality 92) and read back as code values.
cv::Mat jpeg_chart(Encoder e, const std::array<cv::Point2f, 4>& corners) {
    cv::Mat light = synthetic::chart_photo(cast(reference_patches()), {960, 720}, corners);
    cv::Mat noise(light.size(), CV_32FC3);
    cv::RNG(7).fill(noise, cv::RNG::NORMAL, 0.0, 0.004);
    light += noise;
    // Chart coordinates (columns, rows from the top-left corner) into the image.
    const cv::Mat h = cv::getPerspectiveTransform(
        std::vector<cv::Point2f>{{0, 0}, {6, 0}, {6, 4}, {0, 4}}, std::vector<cv::Point2f>(corners.begin(), corners.end()));
    std::vector<cv::Point2f> spots;
    cv::perspectiveTransform(std::vector<cv::Point2f>{{0.55f, 3.45f}, {2.5f, 2.55f}}, spots, h);
    cv::circle(light, spots[0], 6, cv::Scalar::all(3.0), cv::FILLED);  // glint on the white patch
    cv::circle(light, spots[1], 4, cv::Scalar::all(0.0), cv::FILLED);  // dust on the red patch
    cv::Mat bgr8(light.size(), CV_8UC3);
    light.forEach<cv::Vec3f>([&](const cv::Vec3f& px, const int* pos) {
        for (int c = 0; c < 3; ++c)
            bgr8.at<cv::Vec3b>(pos[0], pos[1])[2 - c] = cv::saturate_cast<std::uint8_t>(255 * encode(e, px[c]));
    });
    std::vector<std::uint8_t> jpeg;
    cv::imencode(".jpg", bgr8, jpeg, {cv::IMWRITE_JPEG_QUALITY, 92});
    cv::Mat rgb, codes;
    cv::cvtColor(cv::imdecode(jpeg, cv::IMREAD_COLOR), rgb, cv::COLOR_BGR2RGB);
    rgb.convertTo(codes, CV_32FC3, 1.0 / 255);
    return codes;
}

// OpenCV's cv::ccm (mcc module) on the same patch codes and reference, 3x3 matrix, CIEDE2000 loss, with each of its
// linearisations; the best mean CIEDE2000 (by our evaluation) and which it was.
std::pair<double, std::string> best_opencv_ccm(const std::array<Vec3d, kChartPatches>& codes) {
    cv::Mat src(kChartPatches, 1, CV_64FC3), lab(kChartPatches, 1, CV_64FC3);
    for (int i = 0; i < kChartPatches; ++i) {
        const auto& c = codes[static_cast<std::size_t>(i)];
        const auto& l = reference().lab_d65[static_cast<std::size_t>(i)];
        src.at<cv::Vec3d>(i) = {c[0], c[1], c[2]};
        lab.at<cv::Vec3d>(i) = {l.L, l.a, l.b};
    }
    struct Variant {
        const char* name;
        cv::ccm::LINEAR_TYPE type;
        double gamma;
        int degree;
    };
    const std::vector<Variant> variants{{"gamma 2.2", cv::ccm::LINEARIZATION_GAMMA, 2.2, 0},
                                        {"colour polyfit 3", cv::ccm::LINEARIZATION_COLORPOLYFIT, 0, 3},
                                        {"colour log-polyfit 3", cv::ccm::LINEARIZATION_COLORLOGPOLYFIT, 0, 3},
                                        {"grey polyfit 3", cv::ccm::LINEARIZATION_GRAYPOLYFIT, 0, 3},
                                        {"grey log-polyfit 3", cv::ccm::LINEARIZATION_GRAYLOGPOLYFIT, 0, 3}};
    std::pair<double, std::string> best{INFINITY, "none"};
    for (const auto& v : variants) {
        try {
            cv::ccm::ColorCorrectionModel model(src, lab, cv::ccm::COLOR_SPACE_Lab_D65_2);
            model.setCCM_TYPE(cv::ccm::CCM_3x3);
            model.setDistance(cv::ccm::DISTANCE_CIE2000);
            model.setLinear(v.type);
            if (v.gamma > 0) model.setLinearGamma(v.gamma);
            if (v.degree > 0) model.setLinearDegree(v.degree);
            model.run();
            const cv::Mat corrected = model.infer(src, true);  // linear sRGB
            std::array<Vec3d, kChartPatches> out;
            for (int i = 0; i < kChartPatches; ++i) {
                const cv::Vec3d c = corrected.at<cv::Vec3d>(i);
                out[static_cast<std::size_t>(i)] = {c[0], c[1], c[2]};
            }
            const double mean = chart_delta_e(out, reference()).mean;
            if (mean < best.first) best = {mean, v.name};
        } catch (const cv::Exception&) {
            continue;  // a linearisation this OpenCV cannot fit here
        }
    }
    return best;
}

TEST(ColourCorrectionOfJpegs, AutoLinearisationBeatsOpenCVsCcmOnSrgbGammaAndSCurveCharts) {
    const std::array<cv::Point2f, 4> corners{cv::Point2f{180, 140}, {780, 160}, {770, 570}, {190, 555}};
    const std::array<Linearization, 3> expected{Linearization::Srgb, Linearization::Gamma, Linearization::Poly};
    for (const Encoder e : {Encoder::Srgb, Encoder::Gamma22, Encoder::SCurve}) {
        std::array<int, kChartPatches> rejected{};
        const auto codes = sample_patches(jpeg_chart(e, corners), corners, &rejected);
        EXPECT_GT(rejected[kWhitePatch], 0) << "the glint on the white patch is left out";
        EXPECT_GT(rejected[14], 0) << "the dust on the red patch is left out";
        const LinearizationChoice choice = choose_linearization(codes, reference());
        const ColourCorrection fit =
            fit_colour_correction(codes, reference(), choice.family, CcmConstraint::None, CcmObjective::Ciede2000);
        const DeltaEStats after = chart_delta_e(apply_ccm(linearize_patches(codes, fit.curve), fit.ccm), reference());
        // The old pipeline: the codes taken as sRGB, a matrix alone.
        const auto as_srgb = linearize_patches(codes, ToneCurve(Linearization::Srgb));
        const double matrix_only = chart_delta_e(
            apply_ccm(as_srgb, fit_ccm(as_srgb, reference(), CcmConstraint::None, CcmObjective::Ciede2000)),
            reference()).mean;
        const auto [opencv, variant] = best_opencv_ccm(codes);
        std::printf("[ measured ] %s JPEG: auto picks %s (neutral-row log RMS linear %.4f, srgb %.4f, gamma %.4f, "
                    "poly %.4f); mean CIEDE2000 after %.3f (max %.3f); sRGB + matrix only %.3f; OpenCV ccm best %.3f "
                    "(%s)\n",
                    name(e), linearization_name(choice.family).c_str(), choice.neutral_row_log_rms[0],
                    choice.neutral_row_log_rms[1], choice.neutral_row_log_rms[2], choice.neutral_row_log_rms[3],
                    after.mean, after.max, matrix_only, opencv, variant.c_str());
        EXPECT_EQ(choice.family, expected[static_cast<std::size_t>(e)]) << name(e);
        EXPECT_LT(after.mean, 2.0) << name(e);
        EXPECT_LE(after.mean, opencv) << name(e);
    }
}

TEST(ToneCurves, FamiliesAndTheirChecks) {
    EXPECT_EQ(linearization_by_name("poly"), Linearization::Poly);
    EXPECT_THROW(linearization_by_name("log"), Error);
    const ToneCurve gamma(Linearization::Gamma, {{{2.0, 0, 0}, {2.2, 0, 0}, {1.8, 0, 0}}});
    EXPECT_NEAR(gamma(1, 0.5), std::pow(0.5, 2.2), 1e-12);
    EXPECT_EQ(gamma(0, 0.0), 0.0);
    EXPECT_TRUE(gamma.increasing());
    EXPECT_NEAR(ToneCurve(Linearization::Srgb)(0, 0.5), spectrum::srgb_decode(0.5), 1e-12);
    // A poly curve is the cubic inside the chart's range and its tangent (a gamma) outside.
    const ToneCurve poly(Linearization::Poly, {{{2.0, 0.1, 0.02}, {2.0, 0.1, 0.02}, {2.0, 0.1, 0.02}}},
                         {{{std::log(0.1), 0.0}, {std::log(0.1), 0.0}, {std::log(0.1), 0.0}}});
    const double l = std::log(0.05), l0 = std::log(0.1);
    const double at_end = l0 * (2.0 + l0 * (0.1 + l0 * 0.02)), slope = 2.0 + l0 * (0.2 + l0 * 0.06);
    EXPECT_NEAR(std::log(poly(0, 0.05)), at_end + slope * (l - l0), 1e-12);
    EXPECT_TRUE(poly.increasing());
    const ToneCurve bent(Linearization::Poly, {{{0.5, 1.0, 0.0}, {2, 0, 0}, {2, 0, 0}}},
                         {{{std::log(0.05), 0.0}, {std::log(0.05), 0.0}, {std::log(0.05), 0.0}}});
    EXPECT_FALSE(bent.increasing());  // slope 0.5 + 2 L < 0 at the dark end
}

}  // namespace
}  // namespace surfscatter::photo
