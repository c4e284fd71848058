// surfscatter calibrate: lens intrinsics and distortion from photographs of a ChArUco board or chess board.
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/calibration.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::cli {
namespace {

struct Options {
    std::vector<std::string> images;
    std::string board = "charuco";
    std::string squares;
    double square_length = 0.0;
    double marker_length = 0.0;
    std::string dictionary = "4X4_50";
    bool fit_k3 = false;
    std::string output;
};

void parse_squares(const std::string& text, photo::BoardSpec& spec) {
    const auto x = text.find_first_of("xX");
    try {
        if (x == std::string::npos) throw std::invalid_argument(text);
        std::size_t used_w = 0, used_h = 0;
        spec.squares_x = std::stoi(text.substr(0, x), &used_w);
        spec.squares_y = std::stoi(text.substr(x + 1), &used_h);
        if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument(text);
    } catch (const std::exception&) {
        fail("--squares '{}' must be WxH, e.g. 7x5", text);
    }
}

void run(const Options& o) {
    photo::BoardSpec spec;
    spec.type = photo::board_type_by_name(o.board);
    parse_squares(o.squares, spec);
    spec.square_length = o.square_length;
    spec.marker_length = o.marker_length;
    spec.dictionary = o.dictionary;
    photo::validate(spec);

    std::vector<photo::CalibrationInput> views;
    for (const auto& path : o.images) views.push_back({path, photo::read_photo(path).rgb});
    const photo::CalibrationResult result = photo::calibrate_camera(views, spec, o.fit_k3);
    photo::write_camera(o.output, result.camera);

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
                 "(one standard deviation), distortion [%s], RMS reprojection error %.4f px over %zu images -> %s\n",
                 c.image_size.width, c.image_size.height, c.fx(), sd[0], c.fy(), sd[1], c.cx(), sd[2], c.cy(), sd[3],
                 fmt::format("{:.6g}", fmt::join(c.distortion, ", ")).c_str(), c.rms_reprojection_error,
                 result.used.size(), o.output.c_str());
}

const Command command("calibrate", [](CLI::App& app) {
    auto options = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "calibrate",
        "Lens calibration (fx, fy, cx, cy, distortion k1 k2 p1 p2 [k3]) from several photographs of a ChArUco or chess "
        "board; writes an OpenCV YAML camera file. Prints per-image RMS reprojection error as CSV.");
    sub->add_option("images", options->images, "photographs of the board (PNG, JPEG, TIFF, EXR)")->required();
    sub->add_option("--board", options->board, "board type: charuco or chessboard")->capture_default_str();
    sub->add_option("--squares", options->squares, "number of squares WxH, e.g. 7x5")->required();
    sub->add_option("--square-length", options->square_length, "square edge in metres")->required();
    sub->add_option("--marker-length", options->marker_length, "ChArUco marker edge in metres");
    sub->add_option("--dictionary", options->dictionary, "ChArUco ArUco dictionary")->capture_default_str();
    sub->add_flag("--fit-k3", options->fit_k3, "also fit the 6th-order radial term k3 (wide-angle lenses)");
    sub->add_option("-o,--output", options->output, "camera file to write (.yml)")->required();
    sub->callback([options] {
        if (options->board == "charuco" && options->marker_length == 0.0)
            fail("--marker-length is required for a charuco board");
        run(*options);
    });
});

}  // namespace
}  // namespace surfscatter::cli
