#pragma once
// The real photographs of OpenCV's ArUco tutorial in ../shared/data/realdata/photos (README there): paths, their
// camera, and the marker corners OpenCV's own tests require (opencv_contrib modules/aruco/test/
// test_arucodetection.cpp, CV_ArucoTutorial: every coordinate within 1 px). Header-only: tests/photo and tests/cli.
#include <array>
#include <map>
#include <string>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"

namespace surfscatter::photo::real_photos {

inline std::string path(const std::string& name) {
    return std::string(SURFSCATTER_SHARED_DATA) + "/realdata/photos/" + name;
}
inline const std::string kSingleMarkers = path("singlemarkersoriginal.jpg");  // DICT_6X6_250
inline const std::string kGridBoard = path("gboriginal.jpg");                 // tutorial_dict.yml
inline const std::string kDictionary = path("tutorial_dict.yml");
// The grid board of gboriginal.jpg: 5 x 7 markers (ids 0-34 row by row), 40 mm markers and 10 mm gaps.
inline constexpr int kGridMarkersX = 5, kGridMarkersY = 7;
inline constexpr double kGridMarkerLength = 0.04, kGridSeparation = 0.01;

// tutorial_camera_params.yml holds the matrix and distortion only; the photographs are 640 x 480.
inline CameraModel tutorial_camera() {
    cv::FileStorage fs(path("tutorial_camera_params.yml"), cv::FileStorage::READ);
    cv::Mat matrix, distortion;
    fs["camera_matrix"] >> matrix;
    fs["distortion_coefficients"] >> distortion;
    CameraModel camera;
    camera.image_size = {640, 480};
    camera.matrix = cv::Matx33d(matrix);
    camera.distortion.assign(distortion.begin<double>(), distortion.end<double>());
    return camera;
}

using GoldCorners = std::map<int, std::array<float, 8>>;  // id -> x0 y0 x1 y1 x2 y2 x3 y3

inline const GoldCorners& single_markers_gold() {
    static const GoldCorners gold{{40, {359, 310, 404, 310, 410, 350, 362, 350}},
                                  {98, {427, 255, 469, 256, 477, 289, 434, 288}},
                                  {62, {233, 273, 190, 273, 196, 241, 237, 241}},
                                  {23, {298, 185, 334, 186, 335, 212, 297, 211}},
                                  {124, {425, 163, 430, 186, 394, 186, 390, 162}},
                                  {203, {195, 155, 230, 155, 227, 178, 190, 178}}};
    return gold;
}

inline const GoldCorners& grid_board_gold() {
    static const GoldCorners gold{
        {0, {252, 74, 286, 81, 274, 102, 238, 95}},     {1, {295, 82, 330, 89, 319, 111, 282, 104}},
        {2, {338, 91, 375, 99, 365, 121, 327, 113}},    {3, {383, 100, 421, 107, 412, 130, 374, 123}},
        {4, {429, 109, 468, 116, 461, 139, 421, 132}},  {5, {235, 100, 270, 108, 257, 130, 220, 122}},
        {6, {279, 109, 316, 117, 304, 140, 266, 133}},  {7, {324, 119, 362, 126, 352, 150, 313, 143}},
        {8, {371, 128, 410, 136, 400, 161, 360, 152}},  {9, {418, 139, 459, 145, 451, 170, 410, 163}},
        {10, {216, 128, 253, 136, 239, 161, 200, 152}}, {11, {262, 138, 300, 146, 287, 172, 248, 164}},
        {12, {309, 148, 349, 156, 337, 183, 296, 174}}, {13, {358, 158, 398, 167, 388, 194, 346, 185}},
        {14, {407, 169, 449, 176, 440, 205, 397, 196}}, {15, {196, 158, 235, 168, 218, 195, 179, 185}},
        {16, {243, 170, 283, 178, 269, 206, 228, 197}}, {17, {293, 180, 334, 190, 321, 218, 279, 209}},
        {18, {343, 192, 385, 200, 374, 230, 330, 220}}, {19, {395, 203, 438, 211, 429, 241, 384, 233}},
        {20, {174, 192, 215, 201, 197, 231, 156, 221}}, {21, {223, 204, 265, 213, 249, 244, 207, 234}},
        {22, {275, 215, 317, 225, 303, 257, 259, 246}}, {23, {327, 227, 371, 238, 359, 270, 313, 259}},
        {24, {381, 240, 426, 249, 416, 282, 369, 273}}, {25, {151, 228, 193, 238, 173, 271, 130, 260}},
        {26, {202, 241, 245, 251, 228, 285, 183, 274}}, {27, {255, 254, 300, 264, 284, 299, 238, 288}},
        {28, {310, 267, 355, 278, 342, 314, 295, 302}}, {29, {366, 281, 413, 290, 402, 327, 353, 317}},
        {30, {125, 267, 168, 278, 147, 314, 102, 303}}, {31, {178, 281, 223, 293, 204, 330, 157, 317}},
        {32, {233, 296, 280, 307, 263, 346, 214, 333}}, {33, {291, 310, 338, 322, 323, 363, 274, 349}},
        {34, {349, 325, 399, 336, 386, 378, 335, 366}}};
    return gold;
}

}  // namespace surfscatter::photo::real_photos
