#pragma once
// X-Rite (Gretag Macbeth) ColorChecker Classic: locating the chart, reading its 24 patches in linear RGB, fitting
// a 3x3 colour correction matrix to the reference and measuring CIEDE2000 before and after.
//
// Patch order is the chart's: row by row from dark skin (1) to black (24), with the chart held so that the dark
// skin patch is top-left and the grey row at the bottom. Chart corners are the outer corners of the 6x4 patch
// grid, in that order: top-left (dark skin), top-right (bluish green), bottom-right (black), bottom-left (white).
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/ciede2000.hpp"
#include "surfscatter/photo/colour_space.hpp"

namespace surfscatter::photo {

inline constexpr int kChartPatches = 24;
inline constexpr int kChartColumns = 6;
inline constexpr int kChartRows = 4;
inline constexpr int kWhitePatch = 18;  // 0-based index of patch 19 (white 9.5)

// argyll-ref's measurement of the chart: CIELAB under D50 (Gretag Macbeth data, ArgyllCMS).
inline constexpr const char* kArgyllColorChecker = "/usr/share/color/argyll/ref/ColorChecker.cie";

struct ChartReference {
    std::array<Lab, kChartPatches> lab_d50;       // as published
    std::array<Lab, kChartPatches> lab_d65;       // Bradford-adapted to D65 (the white of linear sRGB)
    std::array<Vec3d, kChartPatches> linear_srgb; // the adapted values in linear sRGB (may leave [0, 1])
};

// Reads an IT8/CGATS .cie file with SAMPLE_ID LAB_L LAB_A LAB_B for A01..D06. Throws Error naming file and line.
ChartReference read_chart_reference(const std::filesystem::path& path = kArgyllColorChecker);

// Finds the chart with OpenCV mcc (CCheckerDetector, MCC24) in a linear RGB photo and returns the patch-grid
// corners in the order above (the orientation is the one that fits `reference` best). Throws Error if no chart is
// found.
std::array<cv::Point2f, 4> detect_chart(const cv::Mat& linear_rgb, const ChartReference& reference);

// Mean linear RGB of the central half (in each direction) of every patch, through the homography of the corners.
std::array<Vec3d, kChartPatches> sample_patches(const cv::Mat& linear_rgb, const std::array<cv::Point2f, 4>& corners);

enum class CcmConstraint {
    None,           // ordinary least squares over the 24 patches
    PreserveWhite,  // least squares subject to M * measured_white = reference_white (white balance kept exact)
};

enum class CcmObjective {
    LeastSquares,  // squared error in linear RGB: closed form, dominated by the bright patches
    Ciede2000,     // mean CIEDE2000 over the patches (the figure reported), from the least-squares start
};
CcmObjective ccm_objective_by_name(const std::string& name);  // "ciede2000" | "least-squares"; throws Error

// 3x3 matrix M (row-major) with corrected = M * measured against the reference in linear sRGB. The CIEDE2000
// objective is minimised by Nelder-Mead (cv::DownhillSolver, restarted until it stops improving) over the 9 entries,
// or over the 6 that keep M * measured_white = reference_white.
cv::Matx33d fit_ccm(const std::array<Vec3d, kChartPatches>& measured, const ChartReference& reference,
                    CcmConstraint constraint, CcmObjective objective = CcmObjective::LeastSquares);

// Evens out the light across the chart: every patch divided, channel by channel, by a flat field (the patch means of
// a photograph of a uniform grey card in the chart's place, same camera, position and light) normalised to its mean
// over the patches. Throws Error naming the patch if the flat field is not positive there.
std::array<Vec3d, kChartPatches> flatten_patches(const std::array<Vec3d, kChartPatches>& measured,
                                                 const std::array<Vec3d, kChartPatches>& flat);

// Linear RGB (sRGB primaries, D65) -> CIELAB relative to D65 with Y_white = 1.
Lab linear_srgb_to_lab(const Vec3d& rgb);

struct DeltaEStats {
    std::array<double, kChartPatches> per_patch{};
    double mean = 0.0, max = 0.0;
};
DeltaEStats chart_delta_e(const std::array<Vec3d, kChartPatches>& rgb, const ChartReference& reference);

// corrected = M * rgb for chart patches and for every pixel of a CV_32FC3 linear RGB image.
std::array<Vec3d, kChartPatches> apply_ccm(const std::array<Vec3d, kChartPatches>& rgb, const cv::Matx33d& ccm);
cv::Mat apply_ccm(const cv::Mat& linear_rgb, const cv::Matx33d& ccm);

}  // namespace surfscatter::photo
