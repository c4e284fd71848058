#pragma once
// Synthetic photographs for the photo tests, made with OpenCV: a textured plane z = 0 seen through a pinhole camera
// with OpenCV lens distortion (exact ray casting per sub-pixel, 3x3 supersampling), ArUco markers, ChArUco and
// chess boards, and a ColorChecker chart. Nothing here is committed as an image; the tests generate it. Header-only: tests/photo and tests/cli use it.
#include <array>

#include <opencv2/core.hpp>

#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include <opencv2/aruco.hpp>
#include <opencv2/aruco/charuco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "surfscatter/photo/colour_space.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::photo::synthetic {

// The camera the photo tests photograph with: known intrinsics and a realistic barrel distortion.
inline CameraModel true_camera() {
    CameraModel c;
    c.image_size = {960, 720};
    c.matrix = cv::Matx33d(1010.0, 0.0, 487.5, 0.0, 1006.0, 352.2, 0.0, 0.0, 1.0);
    c.distortion = {-0.16, 0.09, 0.0012, -0.0008, 0.0};
    return c;
}

inline constexpr int kSupersample = 3;

// World -> OpenCV camera (rvec, tvec) of a camera at `eye` looking at `target` with `up` pointing up in the image.
struct Extrinsics {
    cv::Vec3d rvec, tvec;
};
inline Extrinsics look_at(const cv::Vec3d& eye, const cv::Vec3d& target, const cv::Vec3d& up);
// The camera-to-world transform (OpenCV camera axes) of world -> camera extrinsics.
inline cv::Matx44d camera_to_world(const Extrinsics& e);

// Normalised undistorted image coordinates (x/z, y/z) of every sub-pixel of the camera's (distorted) image.
inline cv::Mat sub_pixel_rays(const CameraModel& camera);

// The camera's view of `texture` (CV_8UC1, sRGB code values) lying on z = 0, centred at the origin, `width` x
// `height` metres, its top row towards +y. Background (outside the texture or behind the camera) = `background`
// (0-255 code value). Sub-pixels are averaged in linear light, as a sensor does. Returns CV_32FC1 linear light.
inline cv::Mat render_plane_linear(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                                   const cv::Mat& rays, const Extrinsics& pose, double background);
// The same, as the 8-bit sRGB-encoded photograph a camera would write (CV_8UC1).
inline cv::Mat render_plane(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                     const cv::Mat& rays, const Extrinsics& pose, double background);
// sRGB encoding of a CV_32FC1 linear image to CV_8UC1, and the decoding of CV_8UC1 to CV_32FC3 linear RGB (what
// read_photo gives for an 8-bit photograph).
inline cv::Mat srgb8_from_linear(const cv::Mat& linear);
inline cv::Mat linear_rgb_from_srgb8(const cv::Mat& encoded);

// An ArUco marker whose black square is `marker_length` metres, on a white square twice as wide.
struct MarkerTexture {
    cv::Mat image;
    double size = 0.0;  // metres (width = height)
};
inline MarkerTexture marker_texture(int id, double marker_length, const char* dictionary = "4X4_50");

// A ChArUco board or chess board with a white margin of one square; size in metres.
struct BoardTexture {
    cv::Mat image;
    double width = 0.0, height = 0.0;
};
inline BoardTexture charuco_texture(int squares_x, int squares_y, double square_length, double marker_length,
                             const char* dictionary = "4X4_50");
inline BoardTexture chessboard_texture(int squares_x, int squares_y, double square_length);

// ColorChecker chart with linear RGB `patches` (CV_32FC3 image, `size` pixels, black frame and gaps) warped onto a
// mid-grey background of `image_size`; `corners` receives the patch-grid corners (the order of color_checker.hpp).
inline cv::Mat chart_photo(const std::array<Vec3d, kChartPatches>& patches, cv::Size image_size,
                    const std::array<cv::Point2f, 4>& corners);

// ---- definitions (header-only so that tests/cli can use them too)


inline Extrinsics look_at(const cv::Vec3d& eye, const cv::Vec3d& target, const cv::Vec3d& up) {
    const cv::Vec3d z = cv::normalize(target - eye);
    const cv::Vec3d x = cv::normalize(z.cross(up));
    const cv::Vec3d y = z.cross(x);
    const cv::Matx33d r(x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]);
    Extrinsics e;
    cv::Rodrigues(r, e.rvec);
    e.tvec = -(r * eye);
    return e;
}

inline cv::Matx44d camera_to_world(const Extrinsics& e) {
    cv::Matx33d r;
    cv::Rodrigues(e.rvec, r);
    const cv::Vec3d eye = -(r.t() * e.tvec);
    cv::Matx44d out = cv::Matx44d::eye();
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) out(i, j) = r(j, i);
        out(i, 3) = eye[i];
    }
    return out;
}

inline cv::Mat sub_pixel_rays(const CameraModel& camera) {
    const int w = camera.image_size.width * kSupersample, h = camera.image_size.height * kSupersample;
    cv::Mat points(h * w, 1, CV_32FC2);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            points.at<cv::Vec2f>(y * w + x) = {static_cast<float>((x + 0.5) / kSupersample - 0.5),
                                               static_cast<float>((y + 0.5) / kSupersample - 0.5)};
    cv::Mat rays;
    cv::undistortPoints(points, rays, camera.matrix, camera.distortion, cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 50, 1e-10));
    return rays.reshape(2, h);
}

inline cv::Mat render_plane_linear(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                                   const cv::Mat& rays, const Extrinsics& pose, double background) {
    cv::Matx33d r;
    cv::Rodrigues(pose.rvec, r);
    const cv::Matx33d rt = r.t();
    const cv::Vec3d eye = -(rt * pose.tvec);
    cv::Mat map_x(rays.size(), CV_32FC1), map_y(rays.size(), CV_32FC1);
    for (int y = 0; y < rays.rows; ++y)
        for (int x = 0; x < rays.cols; ++x) {
            const cv::Vec2f n = rays.at<cv::Vec2f>(y, x);
            const cv::Vec3d d = rt * cv::Vec3d(n[0], n[1], 1.0);
            const double t = -eye[2] / d[2];
            float u = -1e6f, v = -1e6f;
            if (t > 0.0) {
                const double px = eye[0] + t * d[0], py = eye[1] + t * d[1];
                u = static_cast<float>((px / width + 0.5) * texture.cols - 0.5);
                v = static_cast<float>((0.5 - py / height) * texture.rows - 0.5);
            }
            map_x.at<float>(y, x) = u;
            map_y.at<float>(y, x) = v;
        }
    cv::Mat linear_texture(texture.size(), CV_32FC1), fine, out;
    for (int y = 0; y < texture.rows; ++y)
        for (int x = 0; x < texture.cols; ++x)
            linear_texture.at<float>(y, x) = static_cast<float>(spectrum::srgb_decode(texture.at<std::uint8_t>(y, x) / 255.0));
    cv::remap(linear_texture, fine, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar::all(spectrum::srgb_decode(background / 255.0)));
    cv::resize(fine, out, camera.image_size, 0, 0, cv::INTER_AREA);
    return out;
}

inline cv::Mat render_plane(const cv::Mat& texture, double width, double height, const CameraModel& camera,
                     const cv::Mat& rays, const Extrinsics& pose, double background) {
    return srgb8_from_linear(render_plane_linear(texture, width, height, camera, rays, pose, background));
}

inline cv::Mat srgb8_from_linear(const cv::Mat& linear) {
    CV_Assert(linear.type() == CV_32FC1);
    cv::Mat out(linear.size(), CV_8UC1);
    for (int y = 0; y < linear.rows; ++y)
        for (int x = 0; x < linear.cols; ++x)
            out.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(255.0 * spectrum::srgb_encode(linear.at<float>(y, x)));
    return out;
}

inline cv::Mat linear_rgb_from_srgb8(const cv::Mat& encoded) {
    CV_Assert(encoded.type() == CV_8UC1);
    cv::Mat rgb8, f;
    cv::cvtColor(encoded, rgb8, cv::COLOR_GRAY2RGB);
    rgb8.convertTo(f, CV_32FC3, 1.0 / 255.0);
    return srgb_decode_image(f);
}

inline MarkerTexture marker_texture(int id, double marker_length, const char* dictionary) {
    // A whole number of texels per cell: drawMarker rounds cell edges to texels, which on a 400-texel 4x4 marker
    // (6 cells of 66.7) moved inner edges by up to a quarter of a pixel of a 200 px marker.
    const auto dict = load_dictionary(dictionary);
    const int side = 60 * (dict->markerSize + 2);
    cv::Mat marker;
    cv::aruco::drawMarker(dict, id, side, marker, 1);
    cv::Mat canvas(2 * side, 2 * side, CV_8UC1, cv::Scalar(255));
    marker.copyTo(canvas(cv::Rect(side / 2, side / 2, side, side)));
    return {canvas, 2.0 * marker_length};
}

inline BoardTexture charuco_texture(int squares_x, int squares_y, double square_length, double marker_length,
                             const char* dictionary) {
    constexpr int kSquare = 120;
    BoardSpec spec;
    spec.squares_x = squares_x, spec.squares_y = squares_y;
    spec.square_length = square_length, spec.marker_length = marker_length, spec.dictionary = dictionary;
    cv::Mat image;
    make_charuco_board(spec)->draw(cv::Size((squares_x + 2) * kSquare, (squares_y + 2) * kSquare), image, kSquare, 1);
    return {image, (squares_x + 2) * square_length, (squares_y + 2) * square_length};
}

inline BoardTexture chessboard_texture(int squares_x, int squares_y, double square_length) {
    constexpr int kSquare = 120;
    cv::Mat image((squares_y + 2) * kSquare, (squares_x + 2) * kSquare, CV_8UC1, cv::Scalar(255));
    for (int j = 0; j < squares_y; ++j)
        for (int i = 0; i < squares_x; ++i)
            if ((i + j) % 2 == 0)
                image(cv::Rect((i + 1) * kSquare, (j + 1) * kSquare, kSquare, kSquare)).setTo(0);
    return {image, (squares_x + 2) * square_length, (squares_y + 2) * square_length};
}

inline cv::Mat chart_photo(const std::array<Vec3d, kChartPatches>& patches, cv::Size image_size,
                    const std::array<cv::Point2f, 4>& corners) {
    // Chart texture: 100 px per patch pitch, 80 px patches, 10 px black gaps, a 40 px black frame.
    constexpr int kPitch = 100, kGap = 10, kFrame = 40;
    cv::Mat chart(kChartRows * kPitch + 2 * kFrame, kChartColumns * kPitch + 2 * kFrame, CV_32FC3,
                  cv::Scalar::all(0.03));
    for (int row = 0; row < kChartRows; ++row)
        for (int col = 0; col < kChartColumns; ++col) {
            const Vec3d& p = patches[static_cast<std::size_t>(row * kChartColumns + col)];
            chart(cv::Rect(kFrame + col * kPitch + kGap, kFrame + row * kPitch + kGap, kPitch - 2 * kGap,
                           kPitch - 2 * kGap))
                .setTo(cv::Scalar(p[0], p[1], p[2]));
        }
    const std::vector<cv::Point2f> grid{{float(kFrame), float(kFrame)},
                                        {float(kFrame + kChartColumns * kPitch), float(kFrame)},
                                        {float(kFrame + kChartColumns * kPitch), float(kFrame + kChartRows * kPitch)},
                                        {float(kFrame), float(kFrame + kChartRows * kPitch)}};
    const cv::Mat h = cv::getPerspectiveTransform(grid, std::vector<cv::Point2f>(corners.begin(), corners.end()));
    cv::Mat out;
    cv::warpPerspective(chart, out, h, image_size, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar::all(0.18));
    return out;
}

}  // namespace surfscatter::photo::synthetic
