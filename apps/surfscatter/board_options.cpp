#include "board_options.hpp"

#include <stdexcept>

#include "option_scope.hpp"
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

namespace {

// Which board type each board option describes (modes named as typed: "--board grid").
const std::string kCharuco = "--board charuco", kChessboard = "--board chessboard", kGrid = "--board grid";
const std::vector<OptionScope> kBoardScopes = {
    {"--squares", {kCharuco, kChessboard}},        {"--square-length", {kCharuco, kChessboard}},
    {"--markers", {kGrid}},                        {"--marker-separation", {kGrid}},
    {"--marker-length", {kCharuco, kGrid}},        {"--dictionary", {kCharuco, kGrid}},
};

}  // namespace

void BoardOptions::add_to(CLI::App& cmd, const std::string& types, const std::string& default_board, bool grid) {
    command = &cmd;
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
    for (const char* option : {"--squares", "--markers", "--square-length", "--marker-separation"})
        if (option_given(*command, option)) return true;
    return false;
}

photo::BoardSpec BoardOptions::spec() const {
    photo::BoardSpec spec;
    spec.type = photo::board_type_by_name(board);
    require_applicable_options(*command, "--board " + board, kBoardScopes);
    spec.dictionary = dictionary;
    spec.marker_length = marker_length;
    if (spec.type == photo::BoardType::Grid) {
        if (markers.empty()) fail("--board grid needs --markers WxH");
        parse_size(markers, "--markers", spec.markers_x, spec.markers_y);
        spec.marker_separation = marker_separation;
    } else {
        if (squares.empty()) fail("--board {} needs --squares WxH", board);
        parse_size(squares, "--squares", spec.squares_x, spec.squares_y);
        spec.square_length = square_length;
    }
    photo::validate(spec);
    return spec;
}

}  // namespace surfscatter::cli
