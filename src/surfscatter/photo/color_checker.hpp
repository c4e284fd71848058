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
#include "surfscatter/photo/tone_curve.hpp"

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

// Robust mean of the central half (in each direction) of every patch, through the homography of the corners, of
// whatever `image` (CV_32FC3) holds (linear light or code values): pixels with a channel more than
// kPatchOutlierSigmas robust standard deviations (1.4826 MAD, at least kPatchOutlierFloor) from the patch's median
// are left out (specular spots, dust, a scratch); `rejected` (if given) counts them per patch.
inline constexpr double kPatchOutlierSigmas = 4.0;
inline constexpr double kPatchOutlierFloor = 1.0 / 255.0;  // one 8-bit code: quantisation is not an outlier
std::array<Vec3d, kChartPatches> sample_patches(const cv::Mat& image, const std::array<cv::Point2f, 4>& corners,
                                                std::array<int, kChartPatches>* rejected = nullptr);

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

// ---- Colour correction with a tone curve (tone_curve.hpp): corrected = M * f(code) per pixel.

// The linearisation `auto` picks: each family's curve fitted per channel to the chart's neutral row (patches
// 19-24) against the reference, up to a scale; the RMS of ln(fitted / reference) over the 18 values for linear,
// srgb, gamma and poly (in that order); the simplest family within kAutoLinearizationTolerance of the best wins.
inline constexpr double kAutoLinearizationTolerance = 0.01;
struct LinearizationChoice {
    Linearization family = Linearization::Srgb;
    std::array<double, 4> neutral_row_log_rms{};  // linear, srgb, gamma, poly
};
LinearizationChoice choose_linearization(const std::array<Vec3d, kChartPatches>& codes,
                                         const ChartReference& reference);

struct ColourCorrection {
    ToneCurve curve;
    cv::Matx33d ccm;
};
// Fits the tone curve of `family` (not Auto) together with the matrix: the curve's coefficients (started from the
// neutral-row fit) by Nelder-Mead over the objective of the least-squares matrix they give (the exact joint fit for
// the least-squares objective), then the matrix for that curve by fit_ccm. `flat_codes`: the flat field's patch
// codes (flatten_patches after linearisation). Throws Error if a code the curve needs is not positive.
ColourCorrection fit_colour_correction(const std::array<Vec3d, kChartPatches>& codes, const ChartReference& reference,
                                       Linearization family, CcmConstraint constraint, CcmObjective objective,
                                       const std::array<Vec3d, kChartPatches>* flat_codes = nullptr);
// The patches as the fit sees them: linearised by `curve` and, with a flat field, evened by it.
std::array<Vec3d, kChartPatches> linearize_patches(const std::array<Vec3d, kChartPatches>& codes,
                                                   const ToneCurve& curve,
                                                   const std::array<Vec3d, kChartPatches>* flat_codes = nullptr);

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
