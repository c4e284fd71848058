#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/compare.hpp"

namespace surfscatter::photo {
namespace {

// A smooth "metal sphere"-like linear image: a broad highlight on a coloured falloff.
cv::Mat highlight_image(cv::Size size, cv::Point2d centre, double width, cv::Vec3f tint) {
    cv::Mat out(size, CV_32FC3);
    for (int y = 0; y < size.height; ++y)
        for (int x = 0; x < size.width; ++x) {
            const double r2 = (std::pow(x - centre.x, 2) + std::pow(y - centre.y, 2)) / (width * width);
            const float v = static_cast<float>(0.05 + 0.8 * std::exp(-r2));
            out.at<cv::Vec3f>(y, x) = v * tint;
        }
    return out;
}

TEST(Compare, ExposureScaleIsTheLeastSquaresFactor) {
    const cv::Mat photo = highlight_image({64, 48}, {30, 20}, 12, {0.9f, 0.7f, 0.5f});
    const cv::Mat render = photo * 0.25;
    EXPECT_NEAR(exposure_scale(photo, render, cv::Mat()), 4.0, 1e-5);
    const ComparisonMetrics m = compare_to_photo(photo, render, cv::Mat(), "scaled");
    EXPECT_NEAR(m.exposure_scale, 4.0, 1e-5);
    EXPECT_LT(m.rmse, 1e-6);
    EXPECT_GT(m.psnr_db, 100.0);
    EXPECT_NEAR(m.ssim, 1.0, 1e-6);
    EXPECT_LT(m.mean_ciede2000, 1e-3);
}

TEST(Compare, MaskRestrictsTheMetrics) {
    cv::Mat photo = highlight_image({64, 48}, {30, 20}, 12, {0.9f, 0.7f, 0.5f});
    cv::Mat render = photo.clone();
    render(cv::Rect(0, 0, 16, 48)).setTo(cv::Scalar(1, 0, 0));  // wrong outside the mask
    cv::Mat mask(48, 64, CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(20, 0, 44, 48)).setTo(255);
    const ComparisonMetrics inside = compare_to_photo(photo, render, mask, "masked");
    EXPECT_NEAR(inside.exposure_scale, 1.0, 1e-6);
    EXPECT_LT(inside.rmse, 1e-6);
    const ComparisonMetrics everywhere = compare_to_photo(photo, render, cv::Mat(), "all");
    EXPECT_GT(everywhere.rmse, 0.05);
}

TEST(Compare, RanksTheWrongRenderingBelowTheRightOne) {
    const cv::Size size(160, 120);
    const cv::Mat photo = highlight_image(size, {80, 55}, 25, {0.95f, 0.75f, 0.45f});  // gold-like
    cv::Mat noise(size, CV_32FC3);
    cv::randn(noise, 0.0, 0.002);  // Monte-Carlo-like noise in the rendering
    const cv::Mat right = (highlight_image(size, {81, 55}, 25.5, {0.95f, 0.75f, 0.45f}) + noise) * 0.5;
    const cv::Mat wrong = highlight_image(size, {80, 55}, 12, {0.9f, 0.9f, 0.9f}) * 0.5;  // too glossy, silver
    const ComparisonMetrics a = compare_to_photo(photo, right, cv::Mat(), "right");
    const ComparisonMetrics b = compare_to_photo(photo, wrong, cv::Mat(), "wrong");
    std::printf("[ measured ] right: RMSE %.4f PSNR %.2f SSIM %.4f dE00 %.3f | wrong: RMSE %.4f PSNR %.2f SSIM %.4f "
                "dE00 %.3f\n", a.rmse, a.psnr_db, a.ssim, a.mean_ciede2000, b.rmse, b.psnr_db, b.ssim, b.mean_ciede2000);
    EXPECT_NEAR(a.exposure_scale, 2.0, 0.05);
    EXPECT_LT(a.rmse, b.rmse);
    EXPECT_GT(a.psnr_db, b.psnr_db);
    EXPECT_GT(a.ssim, b.ssim);
    EXPECT_LT(a.mean_ciede2000, b.mean_ciede2000);

    const cv::Mat sheet = comparison_sheet(photo, {right, wrong}, cv::Mat(), {a, b});
    EXPECT_EQ(sheet.type(), CV_8UC3);
    EXPECT_EQ(sheet.cols, 3 * 480);
    EXPECT_EQ(sheet.rows, 2 * (360 + 64));
}

TEST(Compare, WithAMaskTheSheetShowsTheMasksBoxEnlarged) {
    const cv::Size size(160, 120);
    const cv::Mat photo = highlight_image(size, {80, 55}, 25, {0.95f, 0.75f, 0.45f});
    const cv::Mat render = photo * 0.5;
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    mask(cv::Rect(60, 40, 40, 20)).setTo(255);
    // The 40 x 20 box with a quarter of its size on each side: 60 x 30 from (50, 35).
    EXPECT_EQ(sheet_crop(size, mask), cv::Rect(50, 35, 60, 30));
    EXPECT_EQ(sheet_crop(size, cv::Mat()), cv::Rect(0, 0, 160, 120));
    cv::Mat most(size, CV_8UC1, cv::Scalar(255));
    most(cv::Rect(0, 0, 4, 4)).setTo(0);
    EXPECT_EQ(sheet_crop(size, most), cv::Rect(0, 0, 160, 120));  // nearly everything: the whole image

    const ComparisonMetrics m = compare_to_photo(photo, render, mask, "half");
    const cv::Mat sheet = comparison_sheet(photo, {render}, mask, {m});
    EXPECT_EQ(sheet.cols, 2 * 480);
    EXPECT_EQ(sheet.rows, 2 * (240 + 64));  // tiles of the crop's 2:1 aspect
}

TEST(Compare, BadInputsAreReported) {
    const cv::Mat photo = highlight_image({64, 48}, {30, 20}, 12, {1, 1, 1});
    EXPECT_THROW(compare_to_photo(photo, cv::Mat(40, 64, CV_32FC3, cv::Scalar::all(0.5)), cv::Mat(), "x"), Error);
    EXPECT_THROW(compare_to_photo(photo, cv::Mat(48, 64, CV_32FC3, cv::Scalar::all(0)), cv::Mat(), "black"), Error);
    EXPECT_THROW(compare_to_photo(photo, photo, cv::Mat(48, 64, CV_8UC1, cv::Scalar(0)), "empty mask"), Error);
}

}  // namespace
}  // namespace surfscatter::photo
