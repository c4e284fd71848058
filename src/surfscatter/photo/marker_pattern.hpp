#pragma once
// Sub-pixel marker corners by fitting the marker's whole known pattern to the photograph (a photometric model).
//
// Why: the edge fit (marker_corners.hpp) needs a border cell of at least 4 px to hold a profile, and the detector's
// own corners are pixel-accurate at best (contour vertices), which on markers of 15-50 px leaves the pose's two
// IPPE solutions almost equally good. The pattern fit uses every edge of the marker, inside as well as outside,
// so it stays accurate down to 2 px per cell. No Debian library offers it (OpenCV's refinements are cornerSubPix,
// contour lines and AprilTag's edge sampling, all local to the outer border), hence written here.
//
// Model of the linear-light image around the marker: I(p) = D + (B - D) * (G_sigma * M)(p), where M(p) is the
// fraction of pixel p that the printed pattern covers in white (the marker's cells, black border, and a white quiet
// zone half a cell wide around it), seen through the homography of the four corners in undistorted pixel
// coordinates and the lens distortion; G_sigma is a Gaussian blur (lens, demosaicing) of the image. D, B, sigma and
// the corners (8 numbers) are fitted by Levenberg-Marquardt (cv::LMSolver) to all pixels of the marker and its
// quiet zone.
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"

namespace surfscatter::photo {

struct PatternFit {
    std::vector<cv::Point2f> corners;  // the detector's order, distorted pixel coordinates
    double residual = 0.0;             // RMS of image - model over the fitted pixels, as a fraction of B - D
    double blur_sigma_px = 0.0;        // fitted Gaussian blur
    double dark = 0.0, bright = 0.0;   // fitted D and B (linear light)
    double corner_std_px = 0.0;        // one standard deviation of a corner coordinate (from the fit's covariance)
};

// `cells`: the printed marker as (bits + 2) x (bits + 2) CV_8UC1 cells, 1 = white, border included, rows from the
// marker's top (marker_cells in markers.hpp). `corners`: a starting guess in the detector's order (top-left,
// top-right, bottom-right, bottom-left of the printed marker), good to about a cell.
//
// fit_marker_pattern fits everything; nothing if the marker and its quiet zone do not lie inside the image with
// room for the blur, the fit does not converge, the contrast is not positive, or a corner moves by more than a cell.
std::optional<PatternFit> fit_marker_pattern(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& corners,
                                             const CameraModel& camera, const cv::Mat& cells);

// How well `corners` explain the image: the model fitted with the corners held fixed (D, B and sigma free); the
// residual is the score by which candidate corner sets are compared. Nothing where fit_marker_pattern gives nothing.
std::optional<PatternFit> score_marker_corners(const cv::Mat& linear_gray, const std::vector<cv::Point2f>& corners,
                                               const CameraModel& camera, const cv::Mat& cells);

}  // namespace surfscatter::photo
