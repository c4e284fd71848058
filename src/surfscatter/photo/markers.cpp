#include "surfscatter/photo/markers.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <limits>
#include <utility>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/photo/file_storage.hpp"
#include "surfscatter/photo/marker_corners.hpp"
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

namespace {
cv::Ptr<cv::aruco::Dictionary> predefined_dictionary(const std::string& name) {
    std::string key = upper(name);
    if (key.rfind("DICT_", 0) == 0) key = key.substr(5);
    for (const auto& [n, id] : kDictionaries)
        if (key == n) return cv::aruco::getPredefinedDictionary(id);
    std::string valid;
    for (const auto& [n, id] : kDictionaries) valid += (valid.empty() ? "" : ", ") + std::string(n);
    fail("unknown ArUco dictionary '{}' (valid: {}, or a dictionary file .yml/.xml/.json)", name, valid);
}

// OpenCV's own Dictionary::readDictionary does not check the bit strings (a longer one writes past its buffer, any
// character but '0' counts as 1), so the file is read and checked here.
cv::Ptr<cv::aruco::Dictionary> dictionary_file(const std::string& path) {
    cv::FileStorage fs;
    open_for_reading(fs, path, "dictionary file");
    const auto integer = [&](const std::string& key, int low, int high) {
        const cv::FileNode node = fs[key];
        if (node.empty()) fail("dictionary file '{}': missing entry '{}'", path, key);
        if (!node.isInt()) fail("dictionary file '{}': '{}' must be an integer", path, key);
        const int value = static_cast<int>(node);
        if (value < low || value > high)
            fail("dictionary file '{}': {} = {} is outside [{}, {}]", path, key, value, low, high);
        return value;
    };
    const int markers = integer("nmarkers", 1, kMaxDictionaryMarkers);
    const int bits = integer("markersize", 2, kMaxMarkerBits);
    const int correction = fs["maxCorrectionBits"].empty() ? 0 : integer("maxCorrectionBits", 0, bits * bits);
    cv::Mat bytes;
    cv::Mat cells(bits, bits, CV_8UC1);
    for (int i = 0; i < markers; ++i) {
        const std::string key = "marker_" + std::to_string(i);
        const cv::FileNode node = fs[key];
        if (node.empty()) fail("dictionary file '{}': missing entry '{}' (nmarkers = {})", path, key, markers);
        if (!node.isString()) fail("dictionary file '{}': '{}' must be a string of '0' and '1'", path, key);
        const std::string code = static_cast<std::string>(node);
        if (code.size() != static_cast<std::size_t>(bits * bits) ||
            code.find_first_not_of("01") != std::string::npos)
            fail("dictionary file '{}': '{}' must be {} characters '0' or '1' (markersize {} squared), got '{}'", path,
                 key, bits * bits, bits, code);
        for (int j = 0; j < bits * bits; ++j) cells.at<std::uint8_t>(j / bits, j % bits) = code[static_cast<std::size_t>(j)] == '1';
        bytes.push_back(cv::aruco::Dictionary::getByteListFromBits(cells));
    }
    return cv::makePtr<cv::aruco::Dictionary>(bytes, bits, correction);
}

void require_length(double value, const char* what) {
    if (!(value >= kMinBoardLength && value <= kMaxBoardLength))
        fail("{} must be between {} and {} metres, got {}", what, kMinBoardLength, kMaxBoardLength, value);
}

void require_side(int value, int minimum, const char* what) {
    if (value < minimum || value > kMaxBoardSide)
        fail("{} must be between {} and {} per side, got {}", what, minimum, kMaxBoardSide, value);
}

void require_dictionary_size(std::int64_t markers, const BoardSpec& board, const char* kind) {
    const int available = load_dictionary(board.dictionary)->bytesList.rows;
    if (markers > available)
        fail("a {} board needs {} markers but dictionary {} has only {}", kind, markers, board.dictionary, available);
}
}  // namespace

cv::Ptr<cv::aruco::Dictionary> load_dictionary(const std::string& name_or_file) {
    if (name_or_file.find_first_of("/.") != std::string::npos) return dictionary_file(name_or_file);
    return predefined_dictionary(name_or_file);
}

cv::Mat marker_cells(const cv::aruco::Dictionary& dictionary, int id) {
    CV_Assert(id >= 0 && id < dictionary.bytesList.rows);
    const int bits = dictionary.markerSize;
    const cv::Mat code = cv::aruco::Dictionary::getBitsFromByteList(dictionary.bytesList.row(id), bits);
    cv::Mat cells = cv::Mat::zeros(bits + 2, bits + 2, CV_8UC1);
    code.copyTo(cells(cv::Rect(1, 1, bits, bits)));
    return cells;
}

cv::Ptr<cv::aruco::DetectorParameters> marker_detector_parameters() {
    auto params = cv::aruco::DetectorParameters::create();
    params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
    return params;
}

DetectedMarkers detect_markers(const cv::Mat& linear_rgb, const cv::Ptr<cv::aruco::Dictionary>& dictionary) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    DetectedMarkers found;
    cv::aruco::detectMarkers(to_gray8(linear_rgb), dictionary, found.corners, found.ids, marker_detector_parameters(),
                             found.rejected);
    return found;
}

BoardType board_type_by_name(const std::string& name) {
    if (name == "charuco") return BoardType::Charuco;
    if (name == "chessboard") return BoardType::Chessboard;
    if (name == "grid") return BoardType::Grid;
    fail("unknown board type '{}' (expected charuco, chessboard or grid)", name);
}

std::string board_type_name(BoardType type) {
    switch (type) {
        case BoardType::Charuco: return "charuco";
        case BoardType::Chessboard: return "chessboard";
        case BoardType::Grid: return "grid";
    }
    return "charuco";  // unreachable: every BoardType is named above
}

void validate(const BoardSpec& board, const BoardParameterNames& names) {
    if (board.type == BoardType::Grid) {
        require_length(board.marker_length, names.marker_length.c_str());
        require_side(board.markers_x, 1, names.markers.c_str());
        require_side(board.markers_y, 1, names.markers.c_str());
        if (board.markers_x * board.markers_y < 2)
            fail("a grid board needs at least 2 markers, got {}x{}", board.markers_x, board.markers_y);
        require_length(board.marker_separation, names.marker_separation.c_str());
        require_dictionary_size(std::int64_t{board.markers_x} * board.markers_y, board, "grid");
        return;
    }
    require_side(board.squares_x, 3, names.squares.c_str());
    require_side(board.squares_y, 3, names.squares.c_str());
    require_length(board.square_length, names.square_length.c_str());
    if (board.type == BoardType::Charuco) {
        require_length(board.marker_length, names.marker_length.c_str());
        if (board.marker_length >= board.square_length)
            fail("{} {} must be smaller than {} {}", names.marker_length, board.marker_length, names.square_length,
                 board.square_length);
        require_dictionary_size(std::int64_t{board.squares_x} * board.squares_y / 2, board, "ChArUco");
    }
}

cv::Ptr<cv::aruco::CharucoBoard> make_charuco_board(const BoardSpec& board) {
    return cv::aruco::CharucoBoard::create(board.squares_x, board.squares_y, static_cast<float>(board.square_length),
                                           static_cast<float>(board.marker_length),
                                           load_dictionary(board.dictionary));
}

cv::Ptr<cv::aruco::GridBoard> make_grid_board(const BoardSpec& board) {
    return cv::aruco::GridBoard::create(board.markers_x, board.markers_y, static_cast<float>(board.marker_length),
                                        static_cast<float>(board.marker_separation), load_dictionary(board.dictionary));
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

// The board's markers in an 8-bit grey image; when some are found, the missed ones are looked for again where the
// board puts them (through the camera if known).
DetectedMarkers detect_board_markers(const cv::Mat& gray, const cv::Ptr<cv::aruco::Board>& board,
                                     const CameraModel* camera) {
    DetectedMarkers found;
    cv::aruco::detectMarkers(gray, board->dictionary, found.corners, found.ids, marker_detector_parameters(),
                             found.rejected);
    if (found.ids.empty()) return found;
    cv::aruco::refineDetectedMarkers(gray, board, found.corners, found.ids, found.rejected,
                                     camera ? cv::Mat(camera->matrix) : cv::Mat(),
                                     camera ? cv::Mat(camera->distortion) : cv::Mat());
    return found;
}

BoardView detect_charuco(const cv::Mat& gray, const BoardSpec& spec, const CameraModel* camera) {
    const auto board = make_charuco_board(spec);
    const DetectedMarkers found = detect_board_markers(gray, board, camera);
    BoardView view;
    if (found.ids.empty()) return view.fail("no marker of the ChArUco board found");
    std::vector<cv::Point2f> corners;
    std::vector<int> ids;
    cv::aruco::interpolateCornersCharuco(found.corners, found.ids, gray, board, corners, ids,
                                         camera ? cv::Mat(camera->matrix) : cv::Mat(),
                                         camera ? cv::Mat(camera->distortion) : cv::Mat());
    view.markers_detected = static_cast<int>(found.ids.size());
    if (static_cast<int>(ids.size()) < kMinimumCharucoCorners)
        return view.fail(fmt::format("too few ChArUco corners: {} interpolated from {} markers, {} needed", ids.size(),
                                     found.ids.size(), kMinimumCharucoCorners));
    if (cv::aruco::testCharucoCornersCollinear(board, ids))
        return view.fail(fmt::format("the {} ChArUco corners found all lie on one line", ids.size()));
    view.image_points = corners;
    for (int id : ids) view.object_points.push_back(board->chessboardCorners[static_cast<std::size_t>(id)]);
    return view;
}

BoardView detect_chessboard(const cv::Mat& gray, const BoardSpec& spec) {
    const cv::Size inner(spec.squares_x - 1, spec.squares_y - 1);
    std::vector<cv::Point2f> corners;
    BoardView view;
    if (!cv::findChessboardCornersSB(gray, inner, corners,
                                     cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_EXHAUSTIVE | cv::CALIB_CB_ACCURACY))
        return view.fail(fmt::format("no {}x{} chessboard found", spec.squares_x, spec.squares_y));
    view.image_points = corners;
    const auto length = static_cast<float>(spec.square_length);
    for (int row = 0; row < inner.height; ++row)
        for (int col = 0; col < inner.width; ++col)
            view.object_points.emplace_back(static_cast<float>(col) * length, static_cast<float>(row) * length, 0.0f);
    return view;
}

// Every marker of the grid found (the missed ones looked for again where the board says they are), each with its
// corners refined by its pattern.
BoardView detect_grid(const cv::Mat& linear_rgb, const cv::Mat& gray, const BoardSpec& spec,
                      const CameraModel& camera) {
    const auto board = make_grid_board(spec);
    const DetectedMarkers found = detect_board_markers(gray, board, &camera);
    BoardView view;
    if (found.ids.empty()) return view.fail("no marker of the grid board found");
    const cv::Mat linear_gray = to_linear_gray(linear_rgb);
    for (std::size_t i = 0; i < found.ids.size(); ++i) {
        const auto position = std::find(board->ids.begin(), board->ids.end(), found.ids[i]);
        if (position == board->ids.end()) continue;  // a marker of the dictionary that is not on this board
        ++view.markers_detected;
        const auto corners = refine_marker(linear_gray, found.corners[i], camera,
                                           marker_cells(*board->dictionary, found.ids[i]))
                                 .corners;
        const auto& object = board->objPoints[static_cast<std::size_t>(position - board->ids.begin())];
        view.image_points.insert(view.image_points.end(), corners.begin(), corners.end());
        view.object_points.insert(view.object_points.end(), object.begin(), object.end());
    }
    if (view.markers_detected == 0)
        return view.fail(fmt::format("none of the {} markers found belongs to the {}x{} grid board", found.ids.size(),
                                     spec.markers_x, spec.markers_y));
    return view;
}
}  // namespace

BoardView detect_board(const cv::Mat& linear_rgb, const BoardSpec& board, const CameraModel* camera) {
    CV_Assert(linear_rgb.type() == CV_32FC3);
    const cv::Mat gray = to_gray8(linear_rgb);
    if (board.type == BoardType::Grid) {
        if (!camera) fail("a grid board needs the camera (its markers' corners are fitted through the lens)");
        return detect_grid(linear_rgb, gray, board, *camera);
    }
    auto view = board.type == BoardType::Charuco ? detect_charuco(gray, board, camera) : detect_chessboard(gray, board);
    if (view.found()) refine_board_corners(to_linear_gray(linear_rgb), board, view.image_points);
    return view;
}

}  // namespace surfscatter::photo
