#include "board_options.hpp"

#include <stdexcept>

#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

void parse_size(const std::string& text, const char* option, int& width, int& height) {
    const auto x = text.find_first_of("xX");
    try {
        if (x == std::string::npos) throw std::invalid_argument(text);
        std::size_t used_w = 0, used_h = 0;
        width = std::stoi(text.substr(0, x), &used_w);
        height = std::stoi(text.substr(x + 1), &used_h);
        if (used_w != x || used_h != text.size() - x - 1) throw std::invalid_argument(text);
    } catch (const std::exception&) {
        fail("{} '{}' must be WxH with whole numbers, e.g. 7x5", option, text);
    }
}

void BoardOptions::add_to(CLI::App& cmd, const std::string& types, const std::string& default_board, bool grid) {
    board = default_board;
    auto* option = cmd.add_option("--board", board, "board type: " + types);
    if (!default_board.empty()) option->capture_default_str();
    cmd.add_option("--squares", squares, "ChArUco or chess board: number of squares WxH, e.g. 7x5");
    cmd.add_option("--square-length", square_length, "ChArUco or chess board: square edge in metres");
    if (grid) {  // a command without grid boards does not list their options (calibrate)
        cmd.add_option("--markers", markers, "grid board: number of markers WxH, e.g. 5x7");
        cmd.add_option("--marker-separation", marker_separation, "grid board: gap between neighbouring markers, metres");
    }
    cmd.add_option("--marker-length", marker_length,
                   grid ? "marker edge in metres (ChArUco, grid and single markers)" : "ChArUco: marker edge in metres");
    cmd.add_option("--dictionary", dictionary,
                   "ArUco dictionary: a name (4X4_50, 6X6_250, APRILTAG_36H11, ...) or an OpenCV dictionary file "
                   "(.yml/.xml/.json with nmarkers, markersize, marker_0 ...)")
        ->capture_default_str();
}

bool BoardOptions::board_options_given() const {
    return !squares.empty() || !markers.empty() || square_length != 0.0 || marker_separation != 0.0;
}

photo::BoardSpec BoardOptions::spec() const {
    photo::BoardSpec spec;
    spec.type = photo::board_type_by_name(board);
    spec.dictionary = dictionary;
    spec.marker_length = marker_length;
    if (spec.type == photo::BoardType::Grid) {
        if (markers.empty()) fail("--board grid needs --markers WxH");
        if (!squares.empty()) fail("--squares is for charuco and chess boards; a grid board takes --markers WxH");
        if (square_length != 0.0) fail("--square-length is for charuco and chess boards, not a grid board");
        parse_size(markers, "--markers", spec.markers_x, spec.markers_y);
        spec.marker_separation = marker_separation;
    } else {
        if (squares.empty()) fail("--board {} needs --squares WxH", board);
        if (!markers.empty()) fail("--markers is for grid boards; a {} board takes --squares WxH", board);
        if (marker_separation != 0.0) fail("--marker-separation is for grid boards, not a {} board", board);
        if (spec.type == photo::BoardType::Chessboard && marker_length != 0.0)
            fail("--marker-length is for boards with markers, not a chessboard");
        parse_size(squares, "--squares", spec.squares_x, spec.squares_y);
        spec.square_length = square_length;
    }
    photo::validate(spec);
    return spec;
}

}  // namespace surfscatter::cli
