// surfscatter board: a printable calibration board (ChArUco, chessboard, ArUco grid) as PNG and PDF at its size.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "board_options.hpp"
#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/io/pdf.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/photo/board_image.hpp"

namespace surfscatter::cli {
namespace {

constexpr double kMetresPerInch = 0.0254;

struct Options {
    BoardOptions board;
    double dpi = 300.0;
    std::optional<double> margin;  // metres; default one square (ChArUco, chess) or one marker (grid)
    std::string output;
};

// The options that describe the board to calibrate and pose, to be pasted after them.
std::string board_arguments(const photo::BoardSpec& spec) {
    if (spec.type == photo::BoardType::Grid)
        return fmt::format("--board grid --markers {}x{} --marker-length {:g} --marker-separation {:g} --dictionary {}",
                           spec.markers_x, spec.markers_y, spec.marker_length, spec.marker_separation,
                           spec.dictionary);
    if (spec.type == photo::BoardType::Chessboard)
        return fmt::format("--board chessboard --squares {}x{} --square-length {:g}", spec.squares_x, spec.squares_y,
                           spec.square_length);
    return fmt::format("--board charuco --squares {}x{} --square-length {:g} --marker-length {:g} --dictionary {}",
                       spec.squares_x, spec.squares_y, spec.square_length, spec.marker_length, spec.dictionary);
}

void run(const Options& o) {
    const photo::BoardSpec spec = o.board.spec();
    if (!(o.dpi > 0.0 && o.dpi <= 10000.0)) fail("--dpi {} must lie in (0, 10000]", o.dpi);
    const std::filesystem::path output(o.output);
    const std::string extension = io::lower_extension(output);
    if (extension != ".png" && extension != ".pdf")
        fail("--output '{}' must end in .png or .pdf (both are written)", o.output);
    const std::filesystem::path png = std::filesystem::path(output).replace_extension(".png");
    const std::filesystem::path pdf = std::filesystem::path(output).replace_extension(".pdf");
    OutputFiles files;
    files.output(png, "--output's PNG");
    files.output(pdf, "--output's PDF");
    const double margin = o.margin ? *o.margin
                          : spec.type == photo::BoardType::Grid ? spec.marker_length
                                                                : spec.square_length;
    if (!(margin >= 0.0 && margin <= photo::kMaxBoardLength))
        fail("--margin {} must lie between 0 and {} m", margin, photo::kMaxBoardLength);

    const photo::BoardImage board = photo::draw_board(spec, o.dpi / kMetresPerInch, margin);
    if (board.width_m > io::kMaxPdfPageMetres || board.height_m > io::kMaxPdfPageMetres)
        fail("the board's page would be {:.0f} x {:.0f} mm, more than a PDF page's {:.0f} mm a side: make the board "
             "smaller", board.width_m * 1e3, board.height_m * 1e3, io::kMaxPdfPageMetres * 1e3);
    io::Raster raster(board.image.cols, board.image.rows, 1, 8);
    for (int y = 0; y < board.image.rows; ++y)
        for (int x = 0; x < board.image.cols; ++x) raster.at(x, y, 0) = board.image.at<std::uint8_t>(y, x);
    raster.pixels_per_metre = board.pixels_per_metre;
    files.write_with(png, [&](const std::filesystem::path& tmp) { io::write_raster(tmp, raster, io::RasterFormat::png); });
    files.write_with(pdf, [&](const std::filesystem::path& tmp) { io::write_image_pdf(tmp, raster, board.width_m, board.height_m); });
    files.commit();

    std::printf("wrote %s (%d x %d px, %.4g dpi) and %s (page %.1f x %.1f mm); print at 100 %% (no fit to page) and "
                "measure a %s with a ruler\n",
                printable_path(png).c_str(), raster.width, raster.height, board.pixels_per_metre * kMetresPerInch,
                printable_path(pdf).c_str(),
                board.width_m * 1e3, board.height_m * 1e3, spec.type == photo::BoardType::Grid ? "marker" : "square");
    std::printf("calibrate and pose with: %s\n", board_arguments(spec).c_str());
}

const Command command("board", [](CLI::App& app) {
    auto options = std::make_shared<Options>();
    auto* sub = app.add_subcommand(
        "board",
        "A printable calibration board for calibrate and pose: ChArUco, chessboard or ArUco grid, written as PNG "
        "(with its density) and as a one-page PDF of the board's physical size. Lengths in metres.");
    options->board.add_to(*sub, "charuco, chessboard or grid", "charuco");
    sub->add_option("--dpi", options->dpi, "pixels per inch of the PNG (rounded to whole pixels per square)")
        ->capture_default_str();
    sub->add_option("--margin", options->margin,
                    "white margin around the board in metres (default: one square; one marker for a grid)");
    sub->add_option("-o,--output", options->output, "board.png or board.pdf: both are written, side by side")
        ->required();
    sub->callback([options] { run(*options); });
});

}  // namespace
}  // namespace surfscatter::cli
