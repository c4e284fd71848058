#include "surfscatter/photo/compare.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>
#include <opencv2/quality/qualityssim.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/ciede2000.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/colour_space.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

namespace {
cv::Mat effective_mask(const cv::Mat& photo, const cv::Mat& render, const cv::Mat& mask) {
    CV_Assert(photo.type() == CV_32FC3 && render.type() == CV_32FC3);
    if (photo.size() != render.size())
        fail("rendering is {}x{} pixels but the photo is {}x{}", render.cols, render.rows, photo.cols, photo.rows);
    if (mask.empty()) return cv::Mat(photo.size(), CV_8UC1, cv::Scalar(255));
    CV_Assert(mask.type() == CV_8UC1);
    if (mask.size() != photo.size())
        fail("mask is {}x{} pixels but the photo is {}x{}", mask.cols, mask.rows, photo.cols, photo.rows);
    if (cv::countNonZero(mask) == 0) fail("mask selects no pixel");
    return mask;
}

double peak_in_mask(const cv::Mat& photo, const cv::Mat& mask) {
    double peak = 0.0;
    for (int y = 0; y < photo.rows; ++y)
        for (int x = 0; x < photo.cols; ++x)
            if (mask.at<std::uint8_t>(y, x))
                for (int c = 0; c < 3; ++c) peak = std::max(peak, double(photo.at<cv::Vec3f>(y, x)[c]));
    if (!(peak > 0.0)) fail("the photo is black inside the mask");
    return peak;
}

// sRGB-encoded, clipped, 0-255 float image of linear / peak (the range QualitySSIM's constants assume).
cv::Mat encoded_for_ssim(const cv::Mat& linear, double peak) {
    cv::Mat scaled = linear / peak;
    cv::Mat clipped = cv::min(cv::max(scaled, 0.0), 1.0);
    return srgb_encode_image(clipped) * 255.0;
}
}  // namespace

double exposure_scale(const cv::Mat& photo, const cv::Mat& render, const cv::Mat& mask) {
    const cv::Mat m = effective_mask(photo, render, mask);
    double pr = 0.0, rr = 0.0;
    for (int y = 0; y < photo.rows; ++y)
        for (int x = 0; x < photo.cols; ++x)
            if (m.at<std::uint8_t>(y, x)) {
                // In double: float products of pixels near 1e38 overflow (rmse was inf).
                const cv::Vec3d p = photo.at<cv::Vec3f>(y, x), r = render.at<cv::Vec3f>(y, x);
                pr += p.dot(r);
                rr += r.dot(r);
            }
    if (!(rr > 0.0)) fail("the rendering is black inside the mask; no exposure can match it");
    return pr / rr;
}

ComparisonMetrics compare_to_photo(const cv::Mat& photo, const cv::Mat& render, const cv::Mat& mask,
                                   const std::string& label) {
    const cv::Mat m = effective_mask(photo, render, mask);
    ComparisonMetrics out;
    out.label = label;
    out.exposure_scale = exposure_scale(photo, render, m);
    const cv::Mat scaled = render * out.exposure_scale;
    const double peak = peak_in_mask(photo, m);

    double sum_sq = 0.0, sum_de = 0.0;
    std::size_t count = 0;
    for (int y = 0; y < photo.rows; ++y)
        for (int x = 0; x < photo.cols; ++x) {
            if (!m.at<std::uint8_t>(y, x)) continue;
            const cv::Vec3f p = photo.at<cv::Vec3f>(y, x), r = scaled.at<cv::Vec3f>(y, x);
            const cv::Vec3d d = cv::Vec3d(p) - cv::Vec3d(r);
            sum_sq += d.dot(d);
            sum_de += ciede2000(linear_srgb_to_lab({p[0], p[1], p[2]}), linear_srgb_to_lab({r[0], r[1], r[2]}));
            ++count;
        }
    const double mse = sum_sq / (3.0 * double(count));
    out.rmse = std::sqrt(mse);
    out.psnr_db = mse > 0.0 ? 10.0 * std::log10(peak * peak / mse) : std::numeric_limits<double>::infinity();
    out.mean_ciede2000 = sum_de / double(count);

    cv::Mat ssim_map;
    cv::quality::QualitySSIM::compute(encoded_for_ssim(photo, peak), encoded_for_ssim(scaled, peak), ssim_map);
    const cv::Scalar ssim = cv::mean(ssim_map, m);
    out.ssim = (ssim[0] + ssim[1] + ssim[2]) / 3.0;
    return out;
}

namespace {
constexpr int kTileWidth = 480;
constexpr int kLabelHeight = 64;

cv::Mat fit_tile(const cv::Mat& bgr8, cv::Size tile) {
    cv::Mat out;
    // Enlarged crops keep their pixels square and sharp: noise and edges as rendered, not smeared.
    cv::resize(bgr8, out, tile, 0, 0, bgr8.cols < tile.width ? cv::INTER_NEAREST : cv::INTER_AREA);
    return out;
}

void put_lines(cv::Mat& canvas, cv::Point origin, const std::vector<std::string>& lines) {
    for (std::size_t i = 0; i < lines.size(); ++i)
        cv::putText(canvas, lines[i], origin + cv::Point(6, 18 + 18 * static_cast<int>(i)), cv::FONT_HERSHEY_SIMPLEX,
                    0.5, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

cv::Mat display(const cv::Mat& linear, double peak) {
    cv::Mat encoded = encoded_for_ssim(linear, peak), bgr, out;
    cv::cvtColor(encoded, bgr, cv::COLOR_RGB2BGR);
    bgr.convertTo(out, CV_8U);
    return out;
}
}  // namespace

cv::Rect sheet_crop(cv::Size size, const cv::Mat& mask) {
    const cv::Rect whole(cv::Point(0, 0), size);
    if (mask.empty() || cv::countNonZero(mask) == 0) return whole;
    const cv::Rect box = cv::boundingRect(mask);
    const int mx = std::max(4, box.width / 4), my = std::max(4, box.height / 4);
    const cv::Rect crop = cv::Rect(box.x - mx, box.y - my, box.width + 2 * mx, box.height + 2 * my) & whole;
    return crop.area() > 0.8 * whole.area() ? whole : crop;
}

cv::Mat comparison_sheet(const cv::Mat& full_photo, const std::vector<cv::Mat>& full_renders, const cv::Mat& mask,
                         const std::vector<ComparisonMetrics>& metrics) {
    CV_Assert(full_renders.size() == metrics.size());
    const cv::Mat full_mask = effective_mask(full_photo, full_photo, mask);
    const double peak = peak_in_mask(full_photo, full_mask);
    const cv::Rect crop = sheet_crop(full_photo.size(), mask);
    const cv::Mat photo = full_photo(crop), m = full_mask(crop);
    std::vector<cv::Mat> renders;
    for (const cv::Mat& r : full_renders) renders.push_back(r(crop));
    const int tile_h = std::max(1, static_cast<int>(std::lround(double(kTileWidth) * photo.rows / photo.cols)));
    const cv::Size tile(kTileWidth, tile_h);
    const int columns = static_cast<int>(renders.size()) + 1;
    cv::Mat sheet(2 * (tile_h + kLabelHeight), columns * kTileWidth, CV_8UC3, cv::Scalar(32, 32, 32));

    // Difference magnitudes |photo - k render| / peak, on one scale for all renderings.
    std::vector<cv::Mat> differences;
    double largest = 0.0;
    for (std::size_t i = 0; i < renders.size(); ++i) {
        cv::Mat diff = photo - renders[i] * metrics[i].exposure_scale, sq, magnitude;
        cv::multiply(diff, diff, sq);
        cv::transform(sq, magnitude, cv::Matx13f(1.0f, 1.0f, 1.0f));
        cv::sqrt(magnitude, magnitude);
        magnitude /= peak;
        magnitude.setTo(0.0, m == 0);
        double mx = 0.0;
        cv::minMaxLoc(magnitude, nullptr, &mx);
        largest = std::max(largest, mx);
        differences.push_back(magnitude);
    }
    const double scale = largest > 0.0 ? 255.0 / largest : 0.0;

    const auto place = [&](const cv::Mat& bgr8, int column, int row, const std::vector<std::string>& lines) {
        const int x = column * kTileWidth, y = row * (tile_h + kLabelHeight);
        put_lines(sheet, {x, y}, lines);
        fit_tile(bgr8, tile).copyTo(sheet(cv::Rect(x, y + kLabelHeight, kTileWidth, tile_h)));
    };
    std::vector<std::string> photo_lines{"photo", fmt::format("peak {:.4g} (shown as white)", peak)};
    if (crop.size() != full_photo.size())
        photo_lines.push_back(fmt::format("mask's box: {}x{} px at ({}, {}) of {}x{}", crop.width, crop.height, crop.x,
                                          crop.y, full_photo.cols, full_photo.rows));
    place(display(photo, peak), 0, 0, photo_lines);
    put_lines(sheet, {0, tile_h + kLabelHeight},
              {"difference |photo - k render| / peak", fmt::format("false colour (inferno) 0 .. {:.3g}", largest)});
    for (std::size_t i = 0; i < renders.size(); ++i) {
        const int column = static_cast<int>(i) + 1;
        const auto& mi = metrics[i];
        place(display(renders[i] * mi.exposure_scale, peak), column, 0,
              {mi.label, fmt::format("k {:.4g}  RMSE {:.4g}  PSNR {:.2f} dB", mi.exposure_scale, mi.rmse, mi.psnr_db),
               fmt::format("SSIM {:.4f}  mean dE00 {:.3f}", mi.ssim, mi.mean_ciede2000)});
        cv::Mat diff8, coloured;
        differences[i].convertTo(diff8, CV_8U, scale);
        cv::applyColorMap(diff8, coloured, cv::COLORMAP_INFERNO);
        place(coloured, column, 1, {mi.label + " difference"});
    }
    return sheet;
}

cv::Mat read_mask(const std::filesystem::path& path, cv::Size photo_size) {
    const cv::Mat mask = read_grey8(path, "mask");
    if (mask.size() != photo_size)
        fail("mask '{}' is {}x{} pixels but the photo is {}x{}", path.string(), mask.cols, mask.rows, photo_size.width,
             photo_size.height);
    return mask;
}

}  // namespace surfscatter::photo
