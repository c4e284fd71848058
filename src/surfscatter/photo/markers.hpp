#pragma once
// ArUco dictionaries and calibration boards (OpenCV 4.6 aruco, the free-function API).
#include <optional>
#include <string>
#include <vector>

#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/core.hpp>

namespace surfscatter::photo {

// "4X4_50", "DICT_6X6_250", "apriltag_36h11" ... (case-insensitive); throws Error listing the valid names.
cv::Ptr<cv::aruco::Dictionary> dictionary_by_name(const std::string& name);

// Detector settings used everywhere: sub-pixel corner refinement (the pose accuracy depends on it).
cv::Ptr<cv::aruco::DetectorParameters> marker_detector_parameters();

enum class BoardType { Charuco, Chessboard };
BoardType board_type_by_name(const std::string& name);  // "charuco" | "chessboard"

struct BoardSpec {
    BoardType type = BoardType::Charuco;
    int squares_x = 0, squares_y = 0;  // squares (not inner corners) along x and y
    double square_length = 0.0;        // metres
    double marker_length = 0.0;        // metres (ChArUco only)
    std::string dictionary = "4X4_50"; // ChArUco only
};

// Throws Error for non-positive sizes, a marker not smaller than a square, or a dictionary too small.
void validate(const BoardSpec& board);

// The OpenCV ChArUco board of a spec (type must be Charuco).
cv::Ptr<cv::aruco::CharucoBoard> make_charuco_board(const BoardSpec& board);

// Corners of the board found in one image: 3-D positions on the board (z = 0, metres) and their pixels.
struct BoardView {
    std::vector<cv::Point3f> object_points;
    std::vector<cv::Point2f> image_points;
};

// Finds the board in a photograph (CV_32FC3 linear light) with sub-pixel corners; nullopt when it is not found (for
// ChArUco: fewer than 6 interpolated corners, or all of them on one line). The board is found on the display
// encoding; the corners are refined on the linear luminance, where a blurred corner is not displaced by the tone
// curve (on sRGB-encoded boards the calibrated principal point moved by about 2 px).
std::optional<BoardView> detect_board(const cv::Mat& linear_rgb, const BoardSpec& board);

}  // namespace surfscatter::photo
