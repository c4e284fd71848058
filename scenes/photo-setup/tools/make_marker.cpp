// Writes textures/aruco_4x4_50_id0.png: ArUco marker id 0 of OpenCV's DICT_4X4_50, 10 pixels per cell, with a
// one-cell white quiet zone (8 x 8 cells = 80 x 80 pixels), so that the 5 cm black square of the scene is 6 cells.
// Build and run (from scenes/photo-setup):
//   g++ -std=c++17 tools/make_marker.cpp $(pkg-config --cflags --libs opencv4) -o /tmp/make_marker && /tmp/make_marker
#include <opencv2/aruco.hpp>
#include <opencv2/imgcodecs.hpp>

int main() {
    const cv::Ptr<cv::aruco::Dictionary> dictionary = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_4X4_50);
    cv::Mat marker;
    cv::aruco::drawMarker(dictionary, 0, 60, marker, 1);
    cv::Mat texture(80, 80, CV_8UC1, cv::Scalar(255));
    marker.copyTo(texture(cv::Rect(10, 10, 60, 60)));
    return cv::imwrite("textures/aruco_4x4_50_id0.png", texture) ? 0 : 1;
}
