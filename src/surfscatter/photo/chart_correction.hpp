#pragma once
// Colour correction of a photograph by the ColorChecker in it, as `surfscatter colorcorrect` runs it and
// surfscatter.colorcorrect (Python) returns it: the chart found (OpenCV mcc) or given, its patches read, the tone
// curve and matrix fitted (color_checker.hpp), the photograph corrected, and CIEDE2000 on the chart before and after.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

// A patch channel of an encoded photograph at or above this fraction of full scale is taken as clipped.
inline constexpr double kClippedCode = 0.995;

struct ChartCorrectionOptions {
    std::optional<std::array<cv::Point2f, 4>> chart_corners;  // the patch grid's outer corners; none: found by mcc
    bool preserve_white = false;
    CcmObjective objective = CcmObjective::Ciede2000;
    std::string linearize = "auto";  // a linearization_by_name name
    std::string reference = kArgyllColorChecker;  // CGATS file of the chart's CIELAB values
    // How messages and the report name these options: the CLI's, unless a front end passes its own.
    std::string chart_corners_option = "--chart-corners", linearize_option = "--linearize";
};

struct ChartCorrection {
    cv::Mat corrected;  // ccm * curve(photo): CV_32FC3 linear sRGB (D65)
    ColourCorrection fit;
    std::array<cv::Point2f, 4> chart_corners;
    std::string chosen_by;             // how the tone curve's family was chosen
    DeltaEStats before, after;         // the chart as the photo shows it, and corrected
    std::vector<std::string> clipped;  // "patch 19 channel G": channels whose code is at the top of the range
    nlohmann::json json;               // what `colorcorrect --ccm` writes, but the names of the input files
};

// `image`: the photograph read with Encoding::Linear (code values of PNG/JPEG/TIFF, linear values of EXR and camera
// RAW); `flat_field`: a photograph of a uniform grey card in the chart's place, read likewise, or null
// (`flat_field_name` names it in errors). Throws Error if given corners leave the image, no chart is found, the flat
// field's size differs or the fit fails (color_checker.hpp).
ChartCorrection correct_with_chart(const Photo& image, const Photo* flat_field, const std::string& flat_field_name,
                                   const ChartCorrectionOptions& options);

}  // namespace surfscatter::photo
