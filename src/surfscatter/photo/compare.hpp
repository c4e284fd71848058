#pragma once
// Photograph versus renderings on one exposure scale, with image metrics and a side-by-side sheet.
//
// All images are CV_32FC3 linear RGB (sRGB primaries, ideally colour-corrected so that 1 is a perfect white).
// Each rendering is first scaled by the factor k minimising sum over the mask of |photo - k render|^2 (all three
// channels); the metrics compare the photo with k * render inside the mask:
//   RMSE   root mean square difference of the linear samples;
//   PSNR   10 log10(peak^2 / MSE) with peak = the photo's largest sample inside the mask;
//   SSIM   OpenCV quality::QualitySSIM (Gaussian window) on the sRGB-encoded images divided by the peak, averaged
//          over the mask and the three channels;
//   dE00   mean CIEDE2000 over the mask, CIELAB relative to the D65 white with Y = 1.
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace surfscatter::photo {

struct ComparisonMetrics {
    std::string label;
    double exposure_scale = 1.0;  // k applied to the rendering
    double rmse = 0.0;
    double psnr_db = 0.0;
    double ssim = 0.0;
    double mean_ciede2000 = 0.0;
};

// Mask: CV_8UC1 of the photo's size, non-zero = compared; empty Mat = the whole image.
// read_mask reads one from an 8-bit image file; throws Error naming it if it is missing, undecodable or not of
// `photo_size`.
cv::Mat read_mask(const std::filesystem::path& path, cv::Size photo_size);
// Throws Error if sizes differ, the mask is empty or the rendering is black inside the mask.
double exposure_scale(const cv::Mat& photo, const cv::Mat& render, const cv::Mat& mask);
ComparisonMetrics compare_to_photo(const cv::Mat& photo, const cv::Mat& render, const cv::Mat& mask,
                                   const std::string& label);

// The sheet: top row photo and exposure-matched renderings (sRGB, divided by the photo's peak), bottom row the
// false-colour (inferno) magnitude of the RGB difference on a common scale, each tile labelled with its metrics.
// With a mask the tiles show the mask's bounding box (sheet_crop), enlarged: the sample, not the room around it.
// Returns 8-bit B, G, R.
cv::Mat comparison_sheet(const cv::Mat& photo, const std::vector<cv::Mat>& renders, const cv::Mat& mask,
                         const std::vector<ComparisonMetrics>& metrics);

// What the sheet shows of an image of `size`: the whole image without a mask (or when the mask's box, with a margin
// of a quarter of its size on each side, would cover more than 80 % of it), else that box.
cv::Rect sheet_crop(cv::Size size, const cv::Mat& mask);

}  // namespace surfscatter::photo
