// surfscatter colorcorrect: 3x3 colour correction matrix from an X-Rite ColorChecker Classic in the photograph.
#include <cstdio>
#include <fstream>
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

struct Options {
    std::string photo;
    std::string chart_corners;
    bool preserve_white = false;
    std::string fit = "ciede2000";
    std::string flat_field;
    std::string reference = photo::kArgyllColorChecker;
    std::string encoding = "srgb";
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

void run(const Options& o) {
    const auto encoding = photo::encoding_by_name(o.encoding);
    const auto objective = photo::ccm_objective_by_name(o.fit);
    const photo::ChartReference reference = photo::read_chart_reference(o.reference);
    const photo::Photo image = photo::read_photo(o.photo, encoding);
    const bool given = !o.chart_corners.empty();
    const auto corners = given ? parse_corners(o.chart_corners, image.rgb.size()) : photo::detect_chart(image.rgb, reference);
    const auto measured = photo::sample_patches(image.rgb, corners);
    // With a flat field the fit sees the chart as if it were evenly lit; the matrix then applies to the whole photo.
    auto evened = measured;
    if (!o.flat_field.empty()) {
        const photo::Photo flat = photo::read_photo(o.flat_field, encoding);
        if (flat.rgb.size() != image.rgb.size())
            fail("flat field '{}' is {}x{} pixels but the photo is {}x{}", o.flat_field, flat.rgb.cols, flat.rgb.rows,
                 image.rgb.cols, image.rgb.rows);
        evened = photo::flatten_patches(measured, photo::sample_patches(flat.rgb, corners));
    }
    const auto constraint = o.preserve_white ? photo::CcmConstraint::PreserveWhite : photo::CcmConstraint::None;
    const cv::Matx33d ccm = photo::fit_ccm(evened, reference, constraint, objective);
    const auto corrected = photo::apply_ccm(evened, ccm);
    const photo::DeltaEStats before = photo::chart_delta_e(measured, reference);
    const photo::DeltaEStats after = photo::chart_delta_e(corrected, reference);

    photo::write_photo(o.output, photo::apply_ccm(image.rgb, ccm), encoding);

    nlohmann::json j;
    j["photo"] = o.photo;
    j["reference"] = o.reference;
    j["chart_detection"] = given ? "given corners" : "OpenCV mcc";
    j["chart_corners_px"] = nlohmann::json::array();
    for (const auto& c : corners) j["chart_corners_px"].push_back({c.x, c.y});
    j["fit"] = fmt::format("{}{}", objective == photo::CcmObjective::Ciede2000 ? "mean CIEDE2000" : "least squares",
                           o.preserve_white ? ", white patch mapped exactly" : "");
    if (!o.flat_field.empty()) {
        j["flat_field"] = o.flat_field;
        j["ciede2000_after_note"] = "patches evened by the flat field, then corrected";
        const photo::DeltaEStats unevened = photo::chart_delta_e(photo::apply_ccm(measured, ccm), reference);
        j["ciede2000_after_without_flat_field"] = {{"mean", unevened.mean}, {"max", unevened.max}};
    }
    j["ccm"] = {{ccm(0, 0), ccm(0, 1), ccm(0, 2)}, {ccm(1, 0), ccm(1, 1), ccm(1, 2)}, {ccm(2, 0), ccm(2, 1), ccm(2, 2)}};
    j["ccm_applies_to"] = "linear RGB column vectors: corrected = ccm * measured; output in linear sRGB (D65)";
    j["ciede2000_before"] = {{"mean", before.mean}, {"max", before.max}, {"per_patch", before.per_patch}};
    j["ciede2000_after"] = {{"mean", after.mean}, {"max", after.max}, {"per_patch", after.per_patch}};
    j["patches_measured_linear_rgb"] = rgb_list(measured);
    j["patches_corrected_linear_rgb"] = rgb_list(corrected);
    j["patches_reference_linear_srgb"] = rgb_list(reference.linear_srgb);
    std::ofstream out(o.ccm_output);
    if (!out) fail("output '{}' could not be written", o.ccm_output);
    out << j.dump(2) << "\n";
    if (!out) fail("output '{}' could not be written", o.ccm_output);

    std::printf("stage,mean_ciede2000,max_ciede2000\n");
    std::printf("before,%s,%s\n", format_number(before.mean).c_str(), format_number(before.max).c_str());
    std::printf("after,%s,%s\n", format_number(after.mean).c_str(), format_number(after.max).c_str());
    std::fprintf(stderr, "surfscatter: colorcorrect: chart %s; CIEDE2000 mean %.3f -> %.3f, max %.3f -> %.3f -> %s, %s\n",
                 given ? "from --chart-corners" : "found by mcc", before.mean, after.mean, before.max, after.max,
                 o.output.c_str(), o.ccm_output.c_str());
}

const Command command("colorcorrect", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "colorcorrect",
        "Colour correction from an X-Rite ColorChecker Classic: finds the chart (OpenCV mcc, or --chart-corners), "
        "reads the 24 patch means in linear RGB, fits a 3x3 matrix to the reference in linear sRGB (D65) and applies "
        "it (optionally after evening out the chart's lighting with a flat-field photo). Prints mean and max "
        "CIEDE2000 on the chart before and after as CSV.");
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
    sub->add_option("--input-encoding", o->encoding, "samples of PNG/JPEG/TIFF inputs: srgb or linear")
        ->capture_default_str();
    sub->add_option("-o,--output", o->output, "corrected image (.png, .tif, .jpg or .exr)")->required();
    sub->add_option("--ccm", o->ccm_output, "JSON with the matrix, patches and CIEDE2000 figures")->required();
    sub->callback([o] { run(*o); });
});

}  // namespace
}  // namespace surfscatter::cli
