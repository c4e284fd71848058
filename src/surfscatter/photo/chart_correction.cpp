#include "surfscatter/photo/chart_correction.hpp"

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

namespace {

using nlohmann::json;

json rgb_list(const std::array<Vec3d, kChartPatches>& values) {
    json out = json::array();
    for (const auto& v : values) out.push_back({v[0], v[1], v[2]});
    return out;
}

json curve_json(const ToneCurve& curve) {
    json j = {{"family", linearization_name(curve.family())}};
    const int k = curve.free_coefficients();
    if (k == 0) return j;
    json channels = json::object();
    for (int c = 0; c < 3; ++c) {
        const auto& coefficients = curve.coefficients()[static_cast<std::size_t>(c)];
        const std::string name(1, "RGB"[c]);
        if (curve.family() == Linearization::Gamma)
            channels[name] = {{"gamma", coefficients[0]}};
        else
            channels[name] = {{"c1", coefficients[0]},
                              {"c2", coefficients[1]},
                              {"c3", coefficients[2]},
                              {"log_code_range", {curve.log_range()[static_cast<std::size_t>(c)][0],
                                                  curve.log_range()[static_cast<std::size_t>(c)][1]}}};
    }
    j["channels"] = channels;
    j["formula"] = curve.family() == Linearization::Gamma
                       ? "linear = code^gamma"
                       : "ln(linear) = c1 L + c2 L^2 + c3 L^3, L = ln(code), continued as the tangent (a gamma) "
                         "outside log_code_range";
    return j;
}

void require_inside(const std::array<cv::Point2f, 4>& corners, cv::Size image_size, const std::string& option) {
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const double x = corners[i].x, y = corners[i].y;
        if (!(x >= 0 && y >= 0 && x <= image_size.width - 1 && y <= image_size.height - 1))
            fail("{}: corner {} ({}, {}) lies outside the {}x{} image", option, i + 1, x, y, image_size.width,
                 image_size.height);
    }
}

}  // namespace

ChartCorrection correct_with_chart(const Photo& image, const Photo* flat_field, const std::string& flat_field_name,
                                   const ChartCorrectionOptions& options) {
    const auto requested = linearization_by_name(options.linearize);
    const ChartReference reference = read_chart_reference(options.reference);
    ChartCorrection out;
    if (options.chart_corners) {
        require_inside(*options.chart_corners, image.rgb.size(), options.chart_corners_option);
        out.chart_corners = *options.chart_corners;
    } else {
        out.chart_corners = detect_chart(image.encoded ? srgb_decode_image(image.rgb) : image.rgb, reference);
    }
    std::array<int, kChartPatches> rejected{};
    const auto codes = sample_patches(image.rgb, out.chart_corners, &rejected);
    std::optional<std::array<Vec3d, kChartPatches>> flat_codes;
    if (flat_field) {
        if (flat_field->rgb.size() != image.rgb.size())
            fail("flat field '{}' is {}x{} pixels but the photo is {}x{}", flat_field_name, flat_field->rgb.cols,
                 flat_field->rgb.rows, image.rgb.cols, image.rgb.rows);
        flat_codes = sample_patches(flat_field->rgb, out.chart_corners);
    }

    // The tone curve's family: as asked, or picked by the neutral row (linear for files that are linear already).
    LinearizationChoice choice;
    out.chosen_by = options.linearize_option + " " + options.linearize;
    if (requested != Linearization::Auto) {
        choice.family = requested;
    } else if (!image.encoded) {
        choice.family = Linearization::Linear;
        out.chosen_by = "auto: the file holds linear values (EXR or camera RAW)";
    } else {
        choice = choose_linearization(codes, reference);
        out.chosen_by = "auto: the simplest family within the tolerance of the best fit to the neutral row";
    }
    const auto constraint = options.preserve_white ? CcmConstraint::PreserveWhite : CcmConstraint::None;
    // OpenCV's simplex asserts when the mean CIEDE2000 it minimises is not finite, as it can be for patches that
    // are no chart: its exception becomes one line naming the corners the patches were taken from.
    try {
        out.fit = fit_colour_correction(codes, reference, choice.family, constraint, options.objective,
                                        flat_codes ? &*flat_codes : nullptr);
    } catch (const cv::Exception& e) {
        std::string corners;
        for (const auto& c : out.chart_corners) corners += fmt::format("{}({}, {})", corners.empty() ? "" : " ", c.x, c.y);
        fail("{}: the colour fit failed on the patches within the corners {} (OpenCV: {}); are they the chart's?",
             options.chart_corners ? options.chart_corners_option : std::string("the chart found in the photo"),
             corners, printable(e.err, 120));
    }
    const cv::Matx33d& ccm = out.fit.ccm;
    // The fit sees the chart linearised (and evened by the flat field); "before" is the photo as it would be shown,
    // its codes taken as sRGB.
    const auto measured = linearize_patches(codes, out.fit.curve);
    const auto evened = linearize_patches(codes, out.fit.curve, flat_codes ? &*flat_codes : nullptr);
    const auto corrected = apply_ccm(evened, ccm);
    const auto as_shown = image.encoded ? linearize_patches(codes, ToneCurve(Linearization::Srgb)) : codes;
    out.before = chart_delta_e(as_shown, reference);
    out.after = chart_delta_e(corrected, reference);
    out.corrected = apply_ccm(out.fit.curve.apply(image.rgb), ccm);
    for (std::size_t i = 0; i < codes.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            if (image.encoded && codes[i][c] >= kClippedCode)
                out.clipped.push_back(fmt::format("patch {} channel {}", i + 1, "RGB"[c]));

    json& j = out.json;
    j["reference"] = options.reference;
    j["chart_detection"] = options.chart_corners ? "given corners" : "OpenCV mcc";
    j["chart_corners_px"] = json::array();
    for (const auto& c : out.chart_corners) j["chart_corners_px"].push_back({c.x, c.y});
    j["fit"] = fmt::format("{}{}, tone curve fitted with the matrix",
                           options.objective == CcmObjective::Ciede2000 ? "mean CIEDE2000" : "least squares",
                           options.preserve_white ? ", white patch mapped exactly" : "");
    j["linearization"] = curve_json(out.fit.curve);
    j["linearization"]["requested"] = options.linearize;
    j["linearization"]["chosen_by"] = out.chosen_by;
    if (requested == Linearization::Auto && image.encoded)
        j["linearization"]["neutral_row_log_rms"] = {{"linear", choice.neutral_row_log_rms[0]},
                                                     {"srgb", choice.neutral_row_log_rms[1]},
                                                     {"gamma", choice.neutral_row_log_rms[2]},
                                                     {"poly", choice.neutral_row_log_rms[3]},
                                                     {"tolerance", kAutoLinearizationTolerance}};
    j["linearization"]["applies_to"] = image.encoded ? "code values / (2^bits - 1) of the photo, per channel"
                                                     : "the file's linear values, per channel";
    if (flat_codes) {
        j["flat_field"] = flat_field_name;
        j["ciede2000_after_note"] = "patches evened by the flat field, then corrected";
        const DeltaEStats unevened = chart_delta_e(apply_ccm(measured, ccm), reference);
        j["ciede2000_after_without_flat_field"] = {{"mean", unevened.mean}, {"max", unevened.max}};
    }
    j["ccm"] = {{ccm(0, 0), ccm(0, 1), ccm(0, 2)}, {ccm(1, 0), ccm(1, 1), ccm(1, 2)}, {ccm(2, 0), ccm(2, 1), ccm(2, 2)}};
    j["ccm_applies_to"] = "linearised RGB column vectors: corrected = ccm * linear; output in linear sRGB (D65)";
    j["ciede2000_before"] = {{"mean", out.before.mean}, {"max", out.before.max}, {"per_patch", out.before.per_patch},
                             {"note", image.encoded ? "the codes shown as sRGB" : "the linear values as they are"}};
    j["ciede2000_after"] = {{"mean", out.after.mean}, {"max", out.after.max}, {"per_patch", out.after.per_patch}};
    j["patch_pixels_rejected"] = rejected;
    j["patches_measured_codes"] = rgb_list(codes);
    j["patches_measured_linear_rgb"] = rgb_list(measured);
    j["patches_corrected_linear_rgb"] = rgb_list(corrected);
    j["patches_reference_linear_srgb"] = rgb_list(reference.linear_srgb);
    j["clipped_patches"] = out.clipped;
    return out;
}

}  // namespace surfscatter::photo
