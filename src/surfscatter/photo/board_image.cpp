#include "surfscatter/photo/board_image.hpp"

#include <cmath>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

BoardImage draw_board(const BoardSpec& board, double pixels_per_metre, double margin_m) {
    validate(board);
    if (!(pixels_per_metre > 0.0 && std::isfinite(pixels_per_metre)))
        fail("board density {} pixels per metre must be positive", pixels_per_metre);
    if (!(margin_m >= 0.0 && margin_m <= kMaxBoardLength))
        fail("board margin {} m must lie between 0 and {} m", margin_m, kMaxBoardLength);
    // The unit drawn a whole number of pixels wide: a square, or a grid's marker.
    const double unit_m = board.type == BoardType::Grid ? board.marker_length : board.square_length;
    const double unit_px = std::round(unit_m * pixels_per_metre);
    if (unit_px < 8.0)
        fail("at {:.4g} dpi a {} of {} mm is {:.3g} pixels, fewer than 8: raise the density", pixels_per_metre * 0.0254,
             board.type == BoardType::Grid ? "marker" : "square", unit_m * 1e3, unit_m * pixels_per_metre);
    BoardImage out;
    out.pixels_per_metre = unit_px / unit_m;
    double width_m = 0.0, height_m = 0.0;
    if (board.type == BoardType::Grid) {
        width_m = board.markers_x * board.marker_length + (board.markers_x - 1) * board.marker_separation;
        height_m = board.markers_y * board.marker_length + (board.markers_y - 1) * board.marker_separation;
    } else {
        width_m = board.squares_x * board.square_length;
        height_m = board.squares_y * board.square_length;
    }
    const double margin_px = std::round(margin_m * out.pixels_per_metre);
    const double board_w = std::round(width_m * out.pixels_per_metre);
    const double board_h = std::round(height_m * out.pixels_per_metre);
    const double image_w = board_w + 2.0 * margin_px, image_h = board_h + 2.0 * margin_px;
    if (image_w > kMaxBoardImageSide || image_h > kMaxBoardImageSide)
        fail("the board would be {:.0f} x {:.0f} pixels at {:.4g} dpi, more than {} a side: lower the density",
             image_w, image_h, pixels_per_metre * 0.0254, kMaxBoardImageSide);
    const cv::Size size(static_cast<int>(image_w), static_cast<int>(image_h));
    const int margin = static_cast<int>(margin_px);
    if (board.type == BoardType::Charuco) {
        make_charuco_board(board)->draw(size, out.image, margin, 1);
    } else if (board.type == BoardType::Grid) {
        make_grid_board(board)->draw(size, out.image, margin, 1);
    } else {
        const int square = static_cast<int>(unit_px);
        out.image = cv::Mat(size, CV_8UC1, cv::Scalar(255));
        // OpenCV's convention (and its ChArUco board's): the top-left square is black.
        for (int j = 0; j < board.squares_y; ++j)
            for (int i = 0; i < board.squares_x; ++i)
                if ((i + j) % 2 == 0)
                    out.image(cv::Rect(margin + i * square, margin + j * square, square, square)).setTo(0);
    }
    out.width_m = size.width / out.pixels_per_metre;
    out.height_m = size.height / out.pixels_per_metre;
    return out;
}

}  // namespace surfscatter::photo
