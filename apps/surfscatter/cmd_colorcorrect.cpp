// surfscatter colorcorrect: 3x3 colour correction matrix from an X-Rite ColorChecker Classic in the photograph.
#include <cstdio>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/photo/chart_correction.hpp"
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
    std::string linearize = "auto";
    std::string output;
    std::string ccm_output;
};

// "x1,y1,...,x4,y4" as the four corners (the library checks that they lie in the image).
std::array<cv::Point2f, 4> parse_corners(const std::string& text) {
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
    for (std::size_t i = 0; i < 4; ++i)
        corners[i] = cv::Point2f(static_cast<float>(values[2 * i]), static_cast<float>(values[2 * i + 1]));
    return corners;
}

void run(const Options& o) {
    OutputFiles files;
    files.input(o.photo, "photo");
    files.input(o.flat_field, "--flat-field");
    files.input(o.reference, "--reference");
    files.output(o.output, "-o");
    files.output(o.ccm_output, "--ccm");
    photo::ChartCorrectionOptions options;
    options.objective = photo::ccm_objective_by_name(o.fit);
    options.preserve_white = o.preserve_white;
    options.linearize = o.linearize;
    options.reference = o.reference;
    if (!o.chart_corners.empty()) options.chart_corners = parse_corners(o.chart_corners);
    // Code values (code / (2^bits - 1)) of PNG/JPEG/TIFF; EXR and camera RAW are linear already.
    const photo::Photo image = photo::read_photo(o.photo, photo::Encoding::Linear);
    std::optional<photo::Photo> flat;
    if (!o.flat_field.empty()) flat = photo::read_photo(o.flat_field, photo::Encoding::Linear);
    photo::ChartCorrection result = photo::correct_with_chart(image, flat ? &*flat : nullptr, o.flat_field, options);

    files.write_with(o.output, [&](const std::filesystem::path& tmp) { photo::write_photo(tmp, result.corrected); });
    nlohmann::json& j = result.json;
    j["photo"] = o.photo;
    files.write(o.ccm_output, j.dump(2) + "\n");
    files.commit();

    const auto& before = result.before;
    const auto& after = result.after;
    std::printf("stage,mean_ciede2000,max_ciede2000\n");
    std::printf("before,%s,%s\n", format_number(before.mean).c_str(), format_number(before.max).c_str());
    std::printf("after,%s,%s\n", format_number(after.mean).c_str(), format_number(after.max).c_str());
    std::fprintf(stderr,
                 "surfscatter: colorcorrect: chart %s; linearisation %s (%s); CIEDE2000 mean %.3f -> %.3f, max %.3f -> "
                 "%.3f -> %s, %s\n",
                 options.chart_corners ? "from --chart-corners" : "found by mcc",
                 photo::linearization_name(result.fit.curve.family()).c_str(), result.chosen_by.c_str(), before.mean,
                 after.mean, before.max, after.max, printable_path(o.output).c_str(), printable_path(o.ccm_output).c_str());
    for (const auto& c : result.clipped)
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
