// surfscatter compare: a photograph against renderings on one exposure scale, with metrics and a sheet.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/photo/compare.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::string photo;
    std::vector<std::string> renders;
    std::string mask;
    std::vector<std::string> labels;
    std::string encoding = "srgb";
    std::string output;
};

// A text field of the CSV (RFC 4180): quoted when it holds a comma, a quote or a line break (a file name may).
std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string quoted = "\"";
    for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

void run(const Options& o) {
    const std::filesystem::path stem = std::filesystem::path(o.output).replace_extension();
    const std::string csv_path = stem.string() + ".csv", json_path = stem.string() + ".json";
    OutputFiles files;
    files.input(o.photo, "photo");
    for (const std::string& render : o.renders) files.input(render, "rendering");
    files.input(o.mask, "--mask");
    files.output(o.output, "-o");
    files.output(csv_path, "-o's CSV");
    files.output(json_path, "-o's JSON");
    if (!o.labels.empty() && o.labels.size() != o.renders.size())
        fail("--labels has {} entries for {} renderings", o.labels.size(), o.renders.size());
    const auto encoding = photo::encoding_by_name(o.encoding);
    const cv::Mat photo_rgb = photo::read_photo(o.photo, encoding).rgb;
    const cv::Mat mask = o.mask.empty() ? cv::Mat() : photo::read_mask(o.mask, photo_rgb.size());
    std::vector<cv::Mat> renders;
    std::vector<photo::ComparisonMetrics> metrics;
    for (std::size_t i = 0; i < o.renders.size(); ++i) {
        renders.push_back(photo::read_photo(o.renders[i], encoding).rgb);
        const std::string label = o.labels.empty() ? std::filesystem::path(o.renders[i]).stem().string() : o.labels[i];
        try {
            metrics.push_back(photo::compare_to_photo(photo_rgb, renders.back(), mask, label));
        } catch (const Error& e) {
            fail("rendering '{}': {}", o.renders[i], e.what());
        }
    }
    const cv::Mat sheet = photo::comparison_sheet(photo_rgb, renders, mask, metrics);
    files.write_with(o.output, [&](const std::filesystem::path& tmp) { photo::write_display_image(tmp, sheet); });

    const std::string header = "label,render,exposure_scale,rmse,psnr_db,ssim,mean_ciede2000";
    std::ostringstream csv;
    csv << header << "\n";
    nlohmann::json j;
    j["photo"] = o.photo;
    j["mask"] = o.mask.empty() ? nlohmann::json(nullptr) : nlohmann::json(o.mask);
    j["renders"] = nlohmann::json::array();
    for (std::size_t i = 0; i < metrics.size(); ++i) {
        const auto& m = metrics[i];
        // PSNR is infinite for an exact match (zero error), the one infinity written on purpose.
        const std::string psnr = std::isinf(m.psnr_db) && m.rmse == 0.0 ? "inf" : format_number(m.psnr_db);
        const std::string row = csv_field(m.label) + "," + csv_field(o.renders[i]) + "," + format_number(m.exposure_scale) + "," +
                                format_number(m.rmse) + "," + psnr + "," + format_number(m.ssim) + "," +
                                format_number(m.mean_ciede2000);
        csv << row << "\n";
        j["renders"].push_back({{"label", m.label},
                                {"file", o.renders[i]},
                                {"exposure_scale", m.exposure_scale},
                                {"rmse", m.rmse},
                                {"psnr_db", m.psnr_db},
                                {"ssim", m.ssim},
                                {"mean_ciede2000", m.mean_ciede2000}});
    }
    // Checked writes (a full disk fails, leaving no partial file).
    files.write(csv_path, csv.str());
    files.write(json_path, j.dump(2) + "\n");
    files.commit();
    std::fputs(csv.str().c_str(), stdout);  // after the files: a failed write prints nothing
    std::fprintf(stderr, "surfscatter: compare: %zu rendering(s) -> %s, %s, %s\n", metrics.size(),
                 printable_path(o.output).c_str(), printable_path(csv_path).c_str(), printable_path(json_path).c_str());
}

const Command command("compare", [](CLI::App& app) {
    auto o = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "compare",
        "Compares a photograph with renderings: each rendering is scaled by the least-squares exposure factor on "
        "the mask, then RMSE, PSNR, SSIM and mean CIEDE2000 inside the mask; writes a labelled sheet (PNG) with "
        "false-colour differences and the metrics as <output>.csv and <output>.json (also printed as CSV).");
    sub->add_option("photo", o->photo, "photograph (linear EXR or PNG/JPEG/TIFF), ideally colour-corrected")->required();
    sub->add_option("renders", o->renders, "renderings of the same size")->required();
    sub->add_option("--mask", o->mask, "8-bit image, non-zero = compared (default: everything)");
    add_string_list(sub, "--labels", o->labels, "one label per rendering, comma-separated");
    sub->add_option("--input-encoding", o->encoding, "samples of PNG/JPEG/TIFF inputs: srgb or linear")
        ->capture_default_str();
    sub->add_option("-o,--output", o->output, "comparison sheet (.png)")->required();
    sub->callback([o] { run(*o); });
});

}  // namespace
}  // namespace surfscatter::cli
