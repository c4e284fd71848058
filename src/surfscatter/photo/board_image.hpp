#pragma once
// Printable calibration boards: the image of a BoardSpec (ChArUco, chessboard, ArUco grid) at a physical pixel
// density, with a white margin, as `surfscatter board` writes it (PNG with its density, and a PDF page of the
// board's size). What calibrate and pose detect is exactly what is drawn here (OpenCV's board drawing).
#include <opencv2/core.hpp>

#include "surfscatter/photo/markers.hpp"

namespace surfscatter::photo {

// Largest board image drawn, pixels a side.
inline constexpr int kMaxBoardImageSide = 30000;

struct BoardImage {
    cv::Mat image;                  // CV_8UC1, 0 black, 255 white, rows from the board's top (its marker 0's edge)
    double pixels_per_metre = 0.0;  // exact: a whole number of pixels per square (ChArUco, chess) or per marker (grid)
    double width_m = 0.0, height_m = 0.0;  // the image's physical size, margins included
};

// Draws `board` (validated) at about `pixels_per_metre` (rounded so that a square, or a grid's marker, is a whole
// number of pixels) with `margin_m` metres of white around it. Throws Error for a density that makes a square
// smaller than 8 pixels or the image larger than kMaxBoardImageSide, or a negative or non-finite margin.
BoardImage draw_board(const BoardSpec& board, double pixels_per_metre, double margin_m);

}  // namespace surfscatter::photo
