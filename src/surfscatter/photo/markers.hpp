#pragma once
// ArUco dictionaries, marker detection and calibration boards (OpenCV 4.6 aruco, the free-function API).
#include <optional>
#include <string>
#include <vector>

#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"

namespace surfscatter::photo {

// A predefined dictionary by name ("4X4_50", "DICT_6X6_250", "apriltag_36h11" ..., case-insensitive) or, when the
// argument contains '/' or '.', a dictionary file in OpenCV's FileStorage format (YAML/XML/JSON): `nmarkers`,
// `markersize` (bits per side) and `marker_0` ... `marker_<nmarkers-1>`, each a string of markersize^2 '0'/'1'
// characters row by row from the marker's top-left (1 = white), and optionally `maxCorrectionBits`.
// Limits: 1 <= nmarkers <= kMaxDictionaryMarkers, 2 <= markersize <= kMaxMarkerBits. Throws Error naming the file
// and the bad entry, or listing the valid names.
inline constexpr int kMaxDictionaryMarkers = 100000;
inline constexpr int kMaxMarkerBits = 16;
cv::Ptr<cv::aruco::Dictionary> load_dictionary(const std::string& name_or_file);

// The printed marker `id` as (bits + 2) x (bits + 2) cells (CV_8UC1, 1 = white, 0 = black), black border included,
// rows from its top.
cv::Mat marker_cells(const cv::aruco::Dictionary& dictionary, int id);

// Detector settings used everywhere: no corner refinement in the detector (its cornerSubPix window is fixed in
// pixels and can reach over several cells of a small marker); corners are refined afterwards, by the marker's
// pattern (marker_corners.hpp) or on the board's chessboard corners.
cv::Ptr<cv::aruco::DetectorParameters> marker_detector_parameters();

// Markers of `dictionary` in a photograph (CV_32FC3 linear light), found on its sRGB-encoded 8-bit grey.
struct DetectedMarkers {
    std::vector<int> ids;
    std::vector<std::vector<cv::Point2f>> corners;  // the detector's, per marker clockwise from its top-left
    std::vector<std::vector<cv::Point2f>> rejected;  // candidates without a valid code (for board refinement)
};
DetectedMarkers detect_markers(const cv::Mat& linear_rgb, const cv::Ptr<cv::aruco::Dictionary>& dictionary);

enum class BoardType { Charuco, Chessboard, Grid };
BoardType board_type_by_name(const std::string& name);  // "charuco" | "chessboard" | "grid"
std::string board_type_name(BoardType type);             // the same names

// Limits of a board (documented in docs/PHOTO.md): squares or markers per side, and lengths in metres.
inline constexpr int kMaxBoardSide = 200;
inline constexpr double kMinBoardLength = 1e-6, kMaxBoardLength = 1e3;

struct BoardSpec {
    BoardType type = BoardType::Charuco;
    int squares_x = 0, squares_y = 0;  // Charuco and Chessboard: squares (not inner corners) along x and y
    double square_length = 0.0;        // metres (Charuco and Chessboard)
    int markers_x = 0, markers_y = 0;  // Grid: markers along x and y
    double marker_separation = 0.0;    // metres between neighbouring markers (Grid)
    double marker_length = 0.0;        // metres (Charuco and Grid)
    std::string dictionary = "4X4_50"; // Charuco and Grid: a name or a file (load_dictionary)
};

// How messages name a board's parameters: the CLI's options, unless a front end passes its own (Python's keywords).
struct BoardParameterNames {
    std::string squares = "--squares", square_length = "--square-length", markers = "--markers",
                marker_length = "--marker-length", marker_separation = "--marker-separation";
};

// Throws Error for sizes outside the limits, lengths not in [kMinBoardLength, kMaxBoardLength], a marker not
// smaller than a square, or a dictionary too small for the board.
void validate(const BoardSpec& board, const BoardParameterNames& names = {});

// The OpenCV boards of a spec (type Charuco, resp. Grid).
cv::Ptr<cv::aruco::CharucoBoard> make_charuco_board(const BoardSpec& board);
cv::Ptr<cv::aruco::GridBoard> make_grid_board(const BoardSpec& board);

// Corners of the board found in one image: 3-D positions on the board (z = 0, metres, OpenCV's board frame) and
// their pixels.
struct BoardView {
    std::vector<cv::Point3f> object_points;
    std::vector<cv::Point2f> image_points;
    int markers_detected = 0;  // ArUco markers of the board found (0 for a chessboard)
    std::string problem;       // why the board cannot be used (not found, too few corners); empty if it can

    bool found() const { return problem.empty(); }
    BoardView& fail(std::string why) {
        problem = std::move(why);
        return *this;
    }
};

// Finds the board in a photograph (CV_32FC3 linear light) with sub-pixel corners. Unusable (`problem` set) when it
// is not found, or (ChArUco) fewer than kMinimumCharucoCorners corners are interpolated or they all lie on one
// line. The board is found on the display encoding; the corners are refined on the linear luminance, where a
// blurred corner is not displaced by the tone curve (on sRGB-encoded boards the calibrated principal point moved by
// about 2 px): ChArUco and chessboard corners by cornerSubPix, a grid board's marker corners by each marker's pattern
// (marker_corners.hpp, which needs `camera`). With `camera`, ChArUco corners are interpolated through the markers'
// poses instead of local homographies, and missed markers are looked for where the board puts them.
inline constexpr int kMinimumCharucoCorners = 6;
BoardView detect_board(const cv::Mat& linear_rgb, const BoardSpec& board, const CameraModel* camera = nullptr);

}  // namespace surfscatter::photo
