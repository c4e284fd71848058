// surfscatter colorcorrect: 3x3 colour correction matrix from an X-Rite ColorChecker Classic in the photograph.
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::cli {
namespace {

// A patch channel at or above this fraction of full scale is taken as clipped.
constexpr double kClippedCode = 0.995;

struct Options {
    std::string photo;
    std::string chart_corners;
    bool preserve_white = false;
    std::string fit = "ciede2000";
    std::string flat_field;
    std::string reference = photo::kArgyllColorChecker;
    std::string linearize = "auto";
    std::string output;
    std::string ccm_output;
};

std::array<cv::Point2f, 4> parse_corners(const std::string& text, cv::Size image_size) {
    std::vector<double> values;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        try {
            std::size_t used = 0;
            values.push_back(std::stod(item, &used));
            if (used != item.size()) throw std::invalid_argument(item);
        } catch (const std::exception&) {
            fail("--chart-corners: '{}' is not a number", item);
        }
    }
    if (values.size() != 8)
        fail("--chart-corners needs 8 numbers x1,y1,...,x4,y4 (top-left, top-right, bottom-right, bottom-left), got {}",
             values.size());
    std::array<cv::Point2f, 4> corners;
    for (std::size_t i = 0; i < 4; ++i) {
        const double x = values[2 * i], y = values[2 * i + 1];
        if (x < 0 || y < 0 || x > image_size.width - 1 || y > image_size.height - 1)
            fail("--chart-corners: corner {} ({}, {}) lies outside the {}x{} image", i + 1, x, y, image_size.width,
                 image_size.height);
        corners[i] = cv::Point2f(static_cast<float>(x), static_cast<float>(y));
    }
    return corners;
}

nlohmann::json rgb_list(const std::array<photo::Vec3d, photo::kChartPatches>& values) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& v : values) out.push_back({v[0], v[1], v[2]});
    return out;
}

nlohmann::json curve_json(const photo::ToneCurve& curve) {
    nlohmann::json j = {{"family", photo::linearization_name(curve.family())}};
    const int k = curve.free_coefficients();
    if (k == 0) return j;
    nlohmann::json channels = nlohmann::json::object();
    for (int c = 0; c < 3; ++c) {
        const auto& coefficients = curve.coefficients()[static_cast<std::size_t>(c)];
        const std::string name(1, "RGB"[c]);
        if (curve.family() == photo::Linearization::Gamma)
            channels[name] = {{"gamma", coefficients[0]}};
        else
            channels[name] = {{"c1", coefficients[0]},
                              {"c2", coefficients[1]},
                              {"c3", coefficients[2]},
                              {"log_code_range", {curve.log_range()[static_cast<std::size_t>(c)][0],
                                                  curve.log_range()[static_cast<std::size_t>(c)][1]}}};
    }
    j["channels"] = channels;
    j["formula"] = curve.family() == photo::Linearization::Gamma
                       ? "linear = code^gamma"
                       : "ln(linear) = c1 L + c2 L^2 + c3 L^3, L = ln(code), continued as the tangent (a gamma) "
                         "outside log_code_range";
    return j;
}

void run(const Options& o) {
    const auto requested = photo::linearization_by_name(o.linearize);
    const auto objective = photo::ccm_objective_by_name(o.fit);
    const photo::ChartReference reference = photo::read_chart_reference(o.reference);
    // Code values (code / (2^bits - 1)) of PNG/JPEG/TIFF; EXR and camera RAW are linear already.
    const photo::Photo image = photo::read_photo(o.photo, photo::Encoding::Linear);
    const bool given = !o.chart_corners.empty();
    const auto corners = given ? parse_corners(o.chart_corners, image.rgb.size())
                               : photo::detect_chart(image.encoded ? photo::srgb_decode_image(image.rgb) : image.rgb,
                                                     reference);
    std::array<int, photo::kChartPatches> rejected{};
    const auto codes = photo::sample_patches(image.rgb, corners, &rejected);
    std::optional<std::array<photo::Vec3d, photo::kChartPatches>> flat_codes;
    if (!o.flat_field.empty()) {
        const photo::Photo flat = photo::read_photo(o.flat_field, photo::Encoding::Linear);
        if (flat.rgb.size() != image.rgb.size())
            fail("flat field '{}' is {}x{} pixels but the photo is {}x{}", o.flat_field, flat.rgb.cols, flat.rgb.rows,
                 image.rgb.cols, image.rgb.rows);
        flat_codes = photo::sample_patches(flat.rgb, corners);
    }

    // The tone curve's family: as asked, or picked by the neutral row (linear for files that are linear already).
    photo::LinearizationChoice choice;
    std::string chosen_by = "--linearize " + o.linearize;
    if (requested != photo::Linearization::Auto) {
        choice.family = requested;
    } else if (!image.encoded) {
        choice.family = photo::Linearization::Linear;
        chosen_by = "auto: the file holds linear values (EXR or camera RAW)";
    } else {
        choice = photo::choose_linearization(codes, reference);
        chosen_by = "auto: the simplest family within the tolerance of the best fit to the neutral row";
    }
    const auto constraint = o.preserve_white ? photo::CcmConstraint::PreserveWhite : photo::CcmConstraint::None;
    const photo::ColourCorrection fit = photo::fit_colour_correction(codes, reference, choice.family, constraint,
                                                                     objective, flat_codes ? &*flat_codes : nullptr);
    const cv::Matx33d& ccm = fit.ccm;
    // The fit sees the chart linearised (and evened by the flat field); "before" is the photo as it would be shown,
    // its codes taken as sRGB.
    const auto measured = photo::linearize_patches(codes, fit.curve);
    const auto evened = photo::linearize_patches(codes, fit.curve, flat_codes ? &*flat_codes : nullptr);
    const auto corrected = photo::apply_ccm(evened, ccm);
    const auto as_shown = image.encoded ? photo::linearize_patches(codes, photo::ToneCurve(photo::Linearization::Srgb))
                                        : codes;
    const photo::DeltaEStats before = photo::chart_delta_e(as_shown, reference);
    const photo::DeltaEStats after = photo::chart_delta_e(corrected, reference);

    photo::write_photo(o.output, photo::apply_ccm(fit.curve.apply(image.rgb), ccm));

    nlohmann::json j;
    j["photo"] = o.photo;
    j["reference"] = o.reference;
    j["chart_detection"] = given ? "given corners" : "OpenCV mcc";
    j["chart_corners_px"] = nlohmann::json::array();
    for (const auto& c : corners) j["chart_corners_px"].push_back({c.x, c.y});
    j["fit"] = fmt::format("{}{}, tone curve fitted with the matrix",
                           objective == photo::CcmObjective::Ciede2000 ? "mean CIEDE2000" : "least squares",
                           o.preserve_white ? ", white patch mapped exactly" : "");
    j["linearization"] = curve_json(fit.curve);
    j["linearization"]["requested"] = o.linearize;
    j["linearization"]["chosen_by"] = chosen_by;
    if (requested == photo::Linearization::Auto && image.encoded)
        j["linearization"]["neutral_row_log_rms"] = {{"linear", choice.neutral_row_log_rms[0]},
                                                     {"srgb", choice.neutral_row_log_rms[1]},
                                                     {"gamma", choice.neutral_row_log_rms[2]},
                                                     {"poly", choice.neutral_row_log_rms[3]},
                                                     {"tolerance", photo::kAutoLinearizationTolerance}};
    j["linearization"]["applies_to"] = image.encoded ? "code values / (2^bits - 1) of the photo, per channel"
                                                     : "the file's linear values, per channel";
    if (flat_codes) {
        j["flat_field"] = o.flat_field;
        j["ciede2000_after_note"] = "patches evened by the flat field, then corrected";
        const photo::DeltaEStats unevened = photo::chart_delta_e(photo::apply_ccm(measured, ccm), reference);
        j["ciede2000_after_without_flat_field"] = {{"mean", unevened.mean}, {"max", unevened.max}};
    }
    j["ccm"] = {{ccm(0, 0), ccm(0, 1), ccm(0, 2)}, {ccm(1, 0), ccm(1, 1), ccm(1, 2)}, {ccm(2, 0), ccm(2, 1), ccm(2, 2)}};
    j["ccm_applies_to"] = "linearised RGB column vectors: corrected = ccm * linear; output in linear sRGB (D65)";
    j["ciede2000_before"] = {{"mean", before.mean}, {"max", before.max}, {"per_patch", before.per_patch},
                             {"note", image.encoded ? "the codes shown as sRGB" : "the linear values as they are"}};
    j["ciede2000_after"] = {{"mean", after.mean}, {"max", after.max}, {"per_patch", after.per_patch}};
    j["patch_pixels_rejected"] = rejected;
    j["patches_measured_codes"] = rgb_list(codes);
    j["patches_measured_linear_rgb"] = rgb_list(measured);
    j["patches_corrected_linear_rgb"] = rgb_list(corrected);
    j["patches_reference_linear_srgb"] = rgb_list(reference.linear_srgb);
    std::vector<std::string> clipped;
    for (std::size_t i = 0; i < codes.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c)
            if (image.encoded && codes[i][c] >= kClippedCode)
                clipped.push_back(fmt::format("patch {} channel {}", i + 1, "RGB"[c]));
    j["clipped_patches"] = clipped;
    std::ofstream out(o.ccm_output);
    if (!out) fail("output '{}' could not be written", o.ccm_output);
    out << j.dump(2) << "\n";
    if (!out) fail("output '{}' could not be written", o.ccm_output);

    std::printf("stage,mean_ciede2000,max_ciede2000\n");
    std::printf("before,%s,%s\n", format_number(before.mean).c_str(), format_number(before.max).c_str());
    std::printf("after,%s,%s\n", format_number(after.mean).c_str(), format_number(after.max).c_str());
    std::fprintf(stderr,
                 "surfscatter: colorcorrect: chart %s; linearisation %s (%s); CIEDE2000 mean %.3f -> %.3f, max %.3f -> "
                 "%.3f -> %s, %s\n",
                 given ? "from --chart-corners" : "found by mcc", photo::linearization_name(fit.curve.family()).c_str(),
                 chosen_by.c_str(), before.mean, after.mean, before.max, after.max, o.output.c_str(),
                 o.ccm_output.c_str());
    for (const auto& c : clipped)
        std::fprintf(stderr,
                     "surfscatter: colorcorrect: warning: %s is clipped (code at the top of the range): its colour "
                     "was not measured; expose less\n",
                     c.c_str());
}

const Command command("colorcorrect", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "colorcorrect",
        "Colour correction from an X-Rite ColorChecker Classic: finds the chart (OpenCV mcc, or --chart-corners), "
        "reads the 24 patches (robust means of their centres), fits a per-channel tone curve and a 3x3 matrix to "
        "the reference in linear sRGB (D65) and applies them (optionally after evening out the chart's lighting with "
        "a flat-field photo). Prints mean and max CIEDE2000 on the chart before and after as CSV.");
    sub->add_option("photo", o->photo, "photograph with the chart (PNG, JPEG, TIFF, EXR)")->required();
    sub->add_option("--chart-corners", o->chart_corners,
                    "x1,y1,...,x4,y4: outer corners of the patch grid, from dark skin (top-left) clockwise");
    sub->add_flag("--preserve-white", o->preserve_white,
                  "constrain the fit so the white patch maps exactly to its reference (white balance kept exact)");
    sub->add_option("--fit", o->fit,
                    "ciede2000 (minimise the mean CIEDE2000 on the chart) or least-squares (in linear RGB)")
        ->capture_default_str();
    sub->add_option("--flat-field", o->flat_field,
                    "photo of a uniform grey card in the chart's place (same camera, position and light): evens out "
                    "the chart's lighting for the fit");
    sub->add_option("--reference", o->reference, "CGATS file with LAB_L LAB_A LAB_B (D50) for A01..D06")
        ->capture_default_str();
    sub->add_option("--linearize", o->linearize,
                    "tone curve from the photo's codes to linear light, fitted with the matrix: auto (picked by the "
                    "chart's neutral row and reported), srgb, linear, gamma (per channel) or poly (per channel, "
                    "log-log cubic); EXR and camera RAW are linear")
        ->capture_default_str();
    sub->add_option("-o,--output", o->output, "corrected image (.png, .tif, .jpg or .exr)")->required();
    sub->add_option("--ccm", o->ccm_output, "JSON with the matrix, patches and CIEDE2000 figures")->required();
    sub->callback([o] { run(*o); });
});

}  // namespace
}  // namespace surfscatter::cli
