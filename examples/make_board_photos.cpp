// Photographs of a printed board, for trying `calibrate` and `pose` without a camera (examples/data/README.md):
// the board image that `surfscatter board` wrote, lying flat, seen from several viewpoints through a known camera
// with barrel distortion (tests/photo/synthetic.hpp: exact ray casting, 3x3 sub-pixels averaged in linear light,
// sRGB-encoded 8-bit PNG). Writes the photographs, the true camera (camera_true.yml: what calibrate should recover)
// and each photograph's true camera-to-board pose (views.json, the board frame of `pose --board`); and, for
// `colorcorrect`, a ColorChecker under a warm cast and uneven light (chart.jpg, JPEG as a camera writes it) with a
// grey card in the same light (grey_card.jpg).
//
//   example-board-photos <board.png> <output folder>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "photo/synthetic.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/color_checker.hpp"
#include "surfscatter/photo/photo_io.hpp"

namespace {

using namespace surfscatter;
namespace synthetic = photo::synthetic;

// A 640 x 480 camera (the tests' lens, scaled): about 51 x 40 degrees, barrel distortion of 3 % at the corners.
photo::CameraModel example_camera() {
    photo::CameraModel c;
    c.image_size = {640, 480};
    c.matrix = cv::Matx33d(673.0, 0.0, 325.0, 0.0, 670.5, 234.8, 0.0, 0.0, 1.0);
    c.distortion = {-0.16, 0.09, 0.0012, -0.0008, 0.0};
    return c;
}

// The light of the chart photograph: a warm cast (the matrix of tests/cli/test_cli_photo.cpp's chart) times a fall-off
// of 30 % from the image's centre to its corners, which only the grey card's flat field removes.
cv::Mat cast_light(const cv::Mat& linear_rgb) {
    const cv::Matx33d cast(0.80, 0.10, -0.02, 0.04, 0.62, 0.08, -0.02, 0.06, 0.45);
    cv::Mat out(linear_rgb.size(), CV_32FC3);
    const double cx = 0.5 * (linear_rgb.cols - 1), cy = 0.5 * (linear_rgb.rows - 1), r2 = cx * cx + cy * cy;
    for (int y = 0; y < linear_rgb.rows; ++y)
        for (int x = 0; x < linear_rgb.cols; ++x) {
            const double falloff = 1.0 - 0.3 * ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2;
            const cv::Vec3f v = linear_rgb.at<cv::Vec3f>(y, x);
            const cv::Vec3d c = falloff * (cast * cv::Vec3d(v[0], v[1], v[2]));
            out.at<cv::Vec3f>(y, x) = cv::Vec3f(float(c[0]), float(c[1]), float(c[2]));
        }
    return out;
}

void write_chart_photos(const std::filesystem::path& folder, cv::Size size) {
    const photo::ChartReference reference = photo::read_chart_reference();
    std::array<photo::Vec3d, photo::kChartPatches> patches;
    for (std::size_t i = 0; i < patches.size(); ++i)
        for (int c = 0; c < 3; ++c) patches[i][c] = std::clamp(reference.linear_srgb[i][c], 0.0, 1.0);
    const std::array<cv::Point2f, 4> corners{cv::Point2f{133, 100}, {507, 113}, {497, 373}, {143, 363}};
    photo::write_photo(folder / "chart.jpg", cast_light(synthetic::chart_photo(patches, size, corners)));
    photo::write_photo(folder / "grey_card.jpg", cast_light(cv::Mat(size, CV_32FC3, cv::Scalar::all(0.45))));
}

int run(const std::filesystem::path& board_png, const std::filesystem::path& folder) {
    const io::Raster raster = io::read_raster(board_png);
    if (raster.channels != 1 || raster.bit_depth != 8 || raster.pixels_per_metre <= 0.0)
        fail("{} is not a board written by `surfscatter board` (8-bit grey PNG with its density)", board_png.string());
    cv::Mat texture(raster.height, raster.width, CV_8UC1);
    for (int y = 0; y < raster.height; ++y)
        for (int x = 0; x < raster.width; ++x)
            texture.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(raster.at(x, y, 0));
    const double width = raster.width / raster.pixels_per_metre, height = raster.height / raster.pixels_per_metre;

    const photo::CameraModel camera = example_camera();
    const cv::Mat rays = synthetic::sub_pixel_rays(camera);
    // The calibration views of tests/cli/test_cli_photo.cpp but its last (seven views are enough and keep the files
    // small): straight on, tilted each way, turned about the axis.
    const std::vector<std::pair<cv::Vec3d, cv::Vec3d>> eyes{
        {{0.0, -0.05, 0.36}, {0, 1, 0}},  {{0.17, 0.0, 0.33}, {0, 1, 0}},    {{-0.17, 0.02, 0.33}, {0, 1, 0}},
        {{0.0, 0.18, 0.31}, {0.3, 1, 0}}, {{0.0, -0.18, 0.31}, {-0.3, 1, 0}}, {{0.13, 0.13, 0.32}, {1, 1, 0}},
        {{-0.13, -0.11, 0.33}, {1, -1, 0}}};
    std::filesystem::create_directories(folder);
    nlohmann::json views = nlohmann::json::array();
    for (std::size_t i = 0; i < eyes.size(); ++i) {
        const auto pose = synthetic::look_at(eyes[i].first, {0, 0, 0}, eyes[i].second);
        const cv::Mat photo = synthetic::render_plane(texture, width, height, camera, rays, pose, 150);
        io::Raster out(photo.cols, photo.rows, 1, 8);
        for (int y = 0; y < photo.rows; ++y)
            for (int x = 0; x < photo.cols; ++x) out.at(x, y, 0) = photo.at<std::uint8_t>(y, x);
        const std::string name = "board" + std::to_string(i + 1) + ".png";
        io::write_raster(folder / name, out, io::RasterFormat::png);
        const cv::Matx44d to_board = synthetic::camera_to_world(pose);
        nlohmann::json matrix = nlohmann::json::array();
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) matrix.push_back(to_board(r, c));
        views.push_back({{"image", name},
                         {"eye_m", {eyes[i].first[0], eyes[i].first[1], eyes[i].first[2]}},
                         {"camera_to_board", matrix}});
    }
    photo::write_camera(folder / "camera_true.yml", camera);
    write_chart_photos(folder, camera.image_size);
    std::ofstream(folder / "views.json")
        << nlohmann::json{{"board", board_png.filename().string()},
                          {"frame", "board frame of `pose --board`: origin at the board's centre, +y to its top, "
                                    "+z towards the camera; OpenCV camera axes (x right, y down, z forward)"},
                          {"views", views}}
               .dump(2)
        << "\n";
    std::printf("wrote %zu board photographs, camera_true.yml, views.json, chart.jpg and grey_card.jpg to %s\n",
                eyes.size(), folder.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: example-board-photos <board.png> <output folder>\n");
        return 2;
    }
    try {
        return run(argv[1], argv[2]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "example-board-photos: error: %s\n", e.what());
        return 2;
    }
}
