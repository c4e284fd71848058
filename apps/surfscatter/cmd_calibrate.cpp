// surfscatter calibrate: lens intrinsics and distortion from photographs of a ChArUco board or chess board.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "board_options.hpp"
#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/photo/calibration.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::vector<std::string> images;
    BoardOptions board;
    bool fit_k3 = false;
    std::string output;
};

void run(const Options& o) {
    OutputFiles files;
    for (const auto& path : o.images) files.input(path, "image");
    files.output(o.output, "-o");
    const photo::BoardSpec spec = o.board.spec();

    std::vector<photo::CalibrationInput> views;
    for (const auto& path : o.images) views.push_back({path, photo::read_photo(path).rgb});
    const photo::CalibrationResult result = photo::calibrate_camera(views, spec, o.fit_k3);
    files.write_with(o.output, [&](const std::filesystem::path& tmp) { photo::write_camera(tmp, result.camera); });
    files.commit();

    const auto& c = result.camera;
    std::printf("image,board_found,rms_reprojection_error_px\n");
    for (std::size_t i = 0; i < result.used.size(); ++i)
        std::printf("%s,yes,%s\n", result.used[i].c_str(), format_number(result.per_view_rms[i]).c_str());
    for (const auto& name : result.rejected) std::printf("%s,no,\n", name.c_str());
    for (const auto& name : result.rejected)
        std::fprintf(stderr, "surfscatter: calibrate: board not found in '%s' (image not used)\n", name.c_str());
    const auto& sd = c.intrinsics_std_dev;
    std::fprintf(stderr,
                 "surfscatter: calibrate: %dx%d, fx %.3f +- %.3f, fy %.3f +- %.3f, cx %.3f +- %.3f, cy %.3f +- %.3f px "
                 "(one standard deviation), distortion [%s], RMS reprojection error %.4f px over %zu images; wrote %s\n",
                 c.image_size.width, c.image_size.height, c.fx(), sd[0], c.fy(), sd[1], c.cx(), sd[2], c.cy(), sd[3],
                 fmt::format("{:.6g}", fmt::join(c.distortion, ", ")).c_str(), c.rms_reprojection_error,
                 result.used.size(), printable_path(o.output).c_str());
    for (const auto& warning : c.calibration_warnings)
        std::fprintf(stderr, "surfscatter: calibrate: warning: %s (recorded in %s)\n", warning.c_str(),
                     printable_path(o.output).c_str());
}

const Command command("calibrate", [](CLI::App& app) {
    auto options = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "calibrate",
        "Lens calibration (fx, fy, cx, cy, distortion k1 k2 p1 p2 [k3]) from several photographs of a ChArUco or chess "
        "board; writes an OpenCV YAML camera file. Prints per-image RMS reprojection error as CSV.");
    sub->add_option("images", options->images, "photographs of the board (PNG, JPEG, TIFF, EXR)")->required();
    options->board.add_to(*sub, "charuco or chessboard", "charuco", false);
    sub->add_flag("--fit-k3", options->fit_k3, "also fit the 6th-order radial term k3 (wide-angle lenses)");
    sub->add_option("-o,--output", options->output, "camera file to write (.yml)")->required();
    sub->callback([options] { run(*options); });
});

}  // namespace
}  // namespace surfscatter::cli
