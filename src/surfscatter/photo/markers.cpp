#include "surfscatter/photo/markers.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <utility>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace surfscatter::photo {

namespace {
constexpr std::array<std::pair<const char*, cv::aruco::PREDEFINED_DICTIONARY_NAME>, 21> kDictionaries{{
    {"4X4_50", cv::aruco::DICT_4X4_50},         {"4X4_100", cv::aruco::DICT_4X4_100},
    {"4X4_250", cv::aruco::DICT_4X4_250},       {"4X4_1000", cv::aruco::DICT_4X4_1000},
    {"5X5_50", cv::aruco::DICT_5X5_50},         {"5X5_100", cv::aruco::DICT_5X5_100},
    {"5X5_250", cv::aruco::DICT_5X5_250},       {"5X5_1000", cv::aruco::DICT_5X5_1000},
    {"6X6_50", cv::aruco::DICT_6X6_50},         {"6X6_100", cv::aruco::DICT_6X6_100},
    {"6X6_250", cv::aruco::DICT_6X6_250},       {"6X6_1000", cv::aruco::DICT_6X6_1000},
    {"7X7_50", cv::aruco::DICT_7X7_50},         {"7X7_100", cv::aruco::DICT_7X7_100},
    {"7X7_250", cv::aruco::DICT_7X7_250},       {"7X7_1000", cv::aruco::DICT_7X7_1000},
    {"ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL}, {"APRILTAG_16H5", cv::aruco::DICT_APRILTAG_16h5},
    {"APRILTAG_25H9", cv::aruco::DICT_APRILTAG_25h9},   {"APRILTAG_36H10", cv::aruco::DICT_APRILTAG_36h10},
    {"APRILTAG_36H11", cv::aruco::DICT_APRILTAG_36h11},
}};

std::string upper(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::toupper(c); });
    return s;
}
}  // namespace

cv::Ptr<cv::aruco::Dictionary> dictionary_by_name(const std::string& name) {
    std::string key = upper(name);
    if (key.rfind("DICT_", 0) == 0) key = key.substr(5);
    for (const auto& [n, id] : kDictionaries)
        if (key == n) return cv::aruco::getPredefinedDictionary(id);
    std::string valid;
    for (const auto& [n, id] : kDictionaries) valid += (valid.empty() ? "" : ", ") + std::string(n);
    fail("unknown ArUco dictionary '{}' (valid: {})", name, valid);
}

cv::Ptr<cv::aruco::DetectorParameters> marker_detector_parameters() {
    auto params = cv::aruco::DetectorParameters::create();
    params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
    params->cornerRefinementWinSize = 5;
    params->cornerRefinementMaxIterations = 100;
    params->cornerRefinementMinAccuracy = 0.001;
    return params;
}

BoardType board_type_by_name(const std::string& name) {
    if (name == "charuco") return BoardType::Charuco;
    if (name == "chessboard") return BoardType::Chessboard;
    fail("unknown board type '{}' (expected charuco or chessboard)", name);
}

void validate(const BoardSpec& board) {
    if (board.squares_x < 3 || board.squares_y < 3)
        fail("board must have at least 3x3 squares, got {}x{}", board.squares_x, board.squares_y);
    require_positive(board.square_length, "--square-length");
    if (board.type == BoardType::Charuco) {
        require_positive(board.marker_length, "--marker-length");
        if (board.marker_length >= board.square_length)
            fail("--marker-length {} must be smaller than --square-length {}", board.marker_length,
                 board.square_length);
        const int markers = board.squares_x * board.squares_y / 2;
        const int available = dictionary_by_name(board.dictionary)->bytesList.rows;
        if (markers > available)
            fail("a {}x{} ChArUco board needs {} markers but dictionary {} has only {}", board.squares_x,
                 board.squares_y, markers, board.dictionary, available);
    }
}

cv::Ptr<cv::aruco::CharucoBoard> make_charuco_board(const BoardSpec& board) {
    return cv::aruco::CharucoBoard::create(board.squares_x, board.squares_y, static_cast<float>(board.square_length),
                                           static_cast<float>(board.marker_length),
                                           dictionary_by_name(board.dictionary));
}

namespace {
// OpenCV 4.6's interpolated ChArUco corners carry a bias of about half a pixel (measured on exactly rendered boards,
// tests/photo/test_calibration.cpp), and any corner found on a gamma-encoded image is displaced by the tone curve; a
// final cornerSubPix on the linear luminance removes both. The window must hold the corner's four squares and nothing
// else: at most 30 % of the smallest corner spacing, and on a ChArUco board it must stop short of the markers, which
// start (square - marker) / 2 from the corner (a window reaching them biased fx by 0.2 %).
void refine_board_corners(const cv::Mat& linear_gray, const BoardSpec& board, std::vector<cv::Point2f>& corners) {
    double spacing = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < corners.size(); ++i)
        for (std::size_t j = i + 1; j < corners.size(); ++j)
            spacing = std::min(spacing, double(cv::norm(corners[i] - corners[j])));
    double fraction = 0.3;
    if (board.type == BoardType::Charuco)
        fraction = std::min(fraction, 0.8 * 0.5 * (board.square_length - board.marker_length) / board.square_length);
    const int half_window = std::clamp(static_cast<int>(fraction * spacing), 2, 10);
    cv::cornerSubPix(linear_gray, corners, cv::Size(half_window, half_window), cv::Size(-1, -1),
                     cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-4));
}

std::optional<BoardView> detect_charuco(const cv::Mat& gray, const BoardSpec& spec) {
    const auto board = make_charuco_board(spec);
    std::vector<std::vector<cv::Point2f>> marker_corners, rejected;
    std::vector<int> marker_ids;
    cv::aruco::detectMarkers(gray, board->dictionary, marker_corners, marker_ids, marker_detector_parameters(),
                             rejected);
    if (marker_ids.empty()) return std::nullopt;
    cv::aruco::refineDetectedMarkers(gray, board, marker_corners, marker_ids, rejected);
    std::vector<cv::Point2f> corners;
    std::vector<int> ids;
    cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, gray, board, corners, ids);
    constexpr int kMinimumCorners = 6;
    if (static_cast<int>(ids.size()) < kMinimumCorners) return std::nullopt;
    if (cv::aruco::testCharucoCornersCollinear(board, ids)) return std::nullopt;
    BoardView view;
    view.image_points = corners;
    for (int id : ids) view.object_points.push_back(board->chessboardCorners[static_cast<std::size_t>(id)]);
    return view;
}

std::optional<BoardView> detect_chessboard(const cv::Mat& gray, const BoardSpec& spec) {
    const cv::Size inner(spec.squares_x - 1, spec.squares_y - 1);
    std::vector<cv::Point2f> corners;
    if (!cv::findChessboardCornersSB(gray, inner, corners,
                                     cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY))
        return std::nullopt;
    BoardView view;
    view.image_points = corners;
    const auto length = static_cast<float>(spec.square_length);
    for (int row = 0; row < inner.height; ++row)
        for (int col = 0; col < inner.width; ++col)
            view.object_points.emplace_back(static_cast<float>(col) * length, static_cast<float>(row) * length, 0.0f);
    return view;
}
}  // namespace

std::optional<BoardView> detect_board(const cv::Mat& linear_rgb, const BoardSpec& board) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    const cv::Mat gray = to_gray8(linear_rgb);
    auto view = board.type == BoardType::Charuco ? detect_charuco(gray, board) : detect_chessboard(gray, board);
    if (view) refine_board_corners(to_linear_gray(linear_rgb), board, view->image_points);
    return view;
}

}  // namespace surfscatter::photo
