#pragma once
// Sub-pixel corners of a square fiducial marker from its four edges, measured in linear light.
//
// Why not OpenCV's corner refinement: cornerSubPix (CORNER_REFINE_SUBPIX) locates an L-shaped corner where the
// image gradients balance. In a gamma-encoded image (what an 8-bit photograph or a display conversion holds) a
// blurred black-to-white edge is asymmetric, and the balance point moves into the dark side: a marker rendered with
// a 0.5 px filter came out 0.3-0.7 px small on every side, which put the camera 9 mm (1.1 %) too far at 0.8 m.
// A blurred step is symmetric in linear light for any symmetric blur, so there its position is exact.
//
// Method: along each side, away from the corners, intensity profiles across the edge give one edge point each (the
// "area" estimate: with the dark level D at the middle of the border cell and the bright level B in the quiet zone,
// the edge sits where the integral of (I - D) / (B - D) over a symmetric window says a sharp step would be). The
// points are undistorted with the camera model, a straight line is fitted to each side (total least squares, with
// outliers beyond 3 robust sigma dropped), neighbouring lines are intersected and the corners distorted back.
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/marker_pattern.hpp"

namespace surfscatter::photo {

// `linear_gray`: CV_32FC1 linear light. `corners`: the detector's four corners in pixels, in its order (clockwise
// from the marker's top-left: the marker's inside is on the right of each side in image coordinates).
// `cells_per_side`: marker bits plus the two border cells (6 for 4x4 dictionaries). Returns nothing if the marker is
// too small (under 4 px per cell), an edge has too few usable profiles (the marker leaves the image or is
// occluded), or a refined corner lands more than a third of a cell from the detector's.
std::optional<std::vector<cv::Point2f>> refine_marker_corners(const cv::Mat& linear_gray,
                                                              const std::vector<cv::Point2f>& corners,
                                                              const CameraModel& camera, int cells_per_side);

// The marker's corners never worse than the detector's. Candidates: the detector's own corners ("detector"),
// cornerSubPix on the linear luminance with a window no wider than a cell ("cornerSubPix", markers of 3 px per cell
// and more), the edge fit above ("edges") and the fit of the whole pattern (marker_pattern.hpp, "pattern", started
// from the best of the others). Each is scored by how well the marker's pattern reprojected through its corners
// explains the image (score_marker_corners: RMS residual as a fraction of the contrast); the lowest wins. When the
// pattern cannot be scored (the marker or its quiet zone leaves the image), the edge fit is kept if it succeeded,
// else the detector's corners.
struct CornerCandidate {
    std::string method;
    std::vector<cv::Point2f> corners;
    std::optional<double> pattern_residual;  // nothing if it could not be scored
};
struct MarkerCorners {
    std::vector<cv::Point2f> corners;         // the chosen set
    std::string method;                       // its candidate's name
    std::vector<CornerCandidate> candidates;  // all of them, in the order above
    std::optional<PatternFit> pattern;        // the pattern fit, when it converged
};
MarkerCorners refine_marker(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& detected,
                            const CameraModel& camera, const cv::Mat& cells);

}  // namespace surfscatter::photo
