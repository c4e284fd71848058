#pragma once
// Board options shared by `surfscatter calibrate` and `surfscatter pose`: --board, --squares WxH, --square-length,
// --markers WxH, --marker-length, --marker-separation, --dictionary.
#include <string>

#include <CLI/CLI.hpp>

#include "surfscatter/photo/markers.hpp"

namespace surfscatter::cli {

struct BoardOptions {
    std::string board;
    std::string squares, markers;
    double square_length = 0.0, marker_length = 0.0, marker_separation = 0.0;
    std::string dictionary = "4X4_50";
    const CLI::App* command = nullptr;  // the command the options were added to (add_to): which of them were given

    // `types` lists the board types the command accepts, for the help text; `default_board` is "" if --board may
    // be left out; `grid`: whether grid boards are among them (--markers, --marker-separation offered).
    void add_to(CLI::App& cmd, const std::string& types, const std::string& default_board, bool grid = true);
    // The spec of --board (validated); throws Error naming the bad option or one its board type does not use
    // (given, even with the default value: --dictionary for a chessboard).
    photo::BoardSpec spec() const;
    // Whether any option that only a board uses was given (--squares, --markers, --square-length,
    // --marker-separation).
    bool board_options_given() const;
};

// Parses "WxH" (e.g. "7x5") of an option `option`; throws Error naming it.
void parse_size(const std::string& text, const char* option, int& width, int& height);

}  // namespace surfscatter::cli
