// `surfscatter board` (printable boards as PNG + PDF at their size) and the example photographs of examples/data,
// which example-board-photos made from such a board: calibrate and pose must recover the camera that took them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <zlib.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

#include "cli/cli_runner.hpp"
#include "photo/synthetic.hpp"
#include "surfscatter/io/raster.hpp"
#include "surfscatter/photo/camera_model.hpp"
#include "surfscatter/photo/markers.hpp"
#include "surfscatter/photo/photo_io.hpp"
#include "surfscatter/heightmap/io.hpp"

namespace surfscatter::photo {
namespace {

namespace fs = std::filesystem;
using test::read_whole_file;
using test::run_cli;
using test::scratch_directory;

const fs::path kExampleData = fs::path(SURFSCATTER_SOURCE_DIR) / "examples" / "data";

// The board image as a camera looking straight at it would see it, `width` px wide, for detect_board.
BoardView detect_in_print(const fs::path& png, const BoardSpec& spec, double width) {
    const cv::Mat image = read_grey8(png, "board");
    cv::Mat small;
    const double scale = width / image.cols;
    cv::resize(image, small, cv::Size(), scale, scale, cv::INTER_AREA);
    return detect_board(synthetic::linear_rgb_from_srgb8(small), spec);
}

// MediaBox and the cross-reference table of a PDF that `board` wrote (every object offset must point at "N 0 obj"),
// and its image: the PNG's samples, deflated.
void expect_valid_pdf(const fs::path& pdf, double width_mm, double height_mm) {
    const std::string text = read_whole_file(pdf.string());
    {
        const io::Raster png = io::read_raster(fs::path(pdf).replace_extension(".png"));
        std::smatch image;
        const std::regex header(R"(/Width (\d+) /Height (\d+) /ColorSpace /DeviceGray )"
                                R"(/BitsPerComponent 8 .*?/Length (\d+) >>\nstream\n)");
        ASSERT_TRUE(std::regex_search(text, image, header));
        EXPECT_EQ(std::stoi(image[1]), png.width);
        EXPECT_EQ(std::stoi(image[2]), png.height);
        std::vector<unsigned char> samples(png.samples.size());
        uLongf size = static_cast<uLongf>(samples.size());
        const std::size_t start = static_cast<std::size_t>(image.position(0) + image.length(0));
        ASSERT_EQ(uncompress(samples.data(), &size, reinterpret_cast<const Bytef*>(text.data() + start),
                             std::stoul(image[3])),
                  Z_OK);
        ASSERT_EQ(size, samples.size());
        EXPECT_TRUE(std::equal(samples.begin(), samples.end(), png.samples.begin()));
    }
    ASSERT_EQ(text.rfind("%PDF-1.4\n", 0), 0u);
    std::smatch box;
    ASSERT_TRUE(std::regex_search(text, box, std::regex(R"(/MediaBox \[0 0 ([0-9.]+) ([0-9.]+)\])")));
    EXPECT_NEAR(std::stod(box[1]) * 25.4 / 72.0, width_mm, 0.1);  // sizes are whole pixels: 0.085 mm at 300 dpi
    EXPECT_NEAR(std::stod(box[2]) * 25.4 / 72.0, height_mm, 0.1);
    const std::size_t startxref = text.rfind("startxref\n");
    ASSERT_NE(startxref, std::string::npos);
    const std::size_t xref = std::stoul(text.substr(startxref + 10));
    ASSERT_EQ(text.compare(xref, 5, "xref\n"), 0);
    for (int object = 1; object <= 5; ++object) {
        const std::size_t offset = std::stoul(text.substr(xref + 5 + 4 + 20 * object, 10));
        EXPECT_EQ(text.compare(offset, std::to_string(object).size() + 6, std::to_string(object) + " 0 obj"), 0)
            << "object " << object;
    }
}

TEST(BoardCli, CharucoPngCarriesItsDensityAndPdfItsSizeAndTheBoardIsFoundInIt) {
    const fs::path dir = scratch_directory("surfscatter_board_cli");
    const auto r = run_cli({"board", "--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022",
                            "--dpi", "150", "-o", (dir / "charuco.png").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // 30 mm at 150 dpi: 177.17 px, drawn as 177 px a square; one square of margin on every side.
    const io::Raster png = io::read_raster(dir / "charuco.png");
    EXPECT_EQ(png.width, 12 * 177);
    EXPECT_EQ(png.height, 9 * 177);
    EXPECT_NEAR(png.pixels_per_metre, 177 / 0.03, 0.5);
    expect_valid_pdf(dir / "charuco.pdf", 360.0, 270.0);
    EXPECT_NE(r.out.find("--board charuco --squares 10x7 --square-length 0.03 --marker-length 0.022"),
              std::string::npos)
        << r.out;

    BoardSpec spec;
    spec.squares_x = 10, spec.squares_y = 7, spec.square_length = 0.03, spec.marker_length = 0.022;
    const BoardView view = detect_in_print(dir / "charuco.png", spec, 1000.0);
    ASSERT_TRUE(view.found()) << view.problem;
    EXPECT_EQ(view.markers_detected, 35);
    EXPECT_EQ(view.image_points.size(), 9u * 6u);
}

TEST(BoardCli, GridAndChessboardsAreFoundInTheirPrints) {
    const fs::path dir = scratch_directory("surfscatter_board_cli");
    auto r = run_cli({"board", "--board", "grid", "--markers", "3x4", "--marker-length", "0.04",
                      "--marker-separation", "0.008", "--dictionary", "6X6_250", "-o", (dir / "grid.pdf").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    // Width 3 x 40 + 2 x 8 = 136 mm, height 4 x 40 + 3 x 8 = 184 mm, one marker (40 mm) of margin.
    expect_valid_pdf(dir / "grid.pdf", 216.0, 264.0);
    BoardSpec grid;
    grid.type = BoardType::Grid, grid.markers_x = 3, grid.markers_y = 4, grid.marker_length = 0.04;
    grid.marker_separation = 0.008, grid.dictionary = "6X6_250";
    // A pinhole looking straight at the print, 400 px wide: a grid's markers are refined with a camera, by their
    // pattern, which on 35 markers of 60-170 px took 10-18 s (load 8 on 2 cores); 12 markers of 90 px here.
    CameraModel camera;
    const io::Raster grid_png = io::read_raster(dir / "grid.png");
    const double scale = 400.0 / grid_png.width;
    camera.image_size = {400, static_cast<int>(std::lround(grid_png.height * scale))};
    camera.matrix = cv::Matx33d(400, 0, 200, 0, 400, camera.image_size.height / 2.0, 0, 0, 1);
    camera.distortion = {0, 0, 0, 0, 0};
    cv::Mat small;
    cv::resize(read_grey8(dir / "grid.png", "board"), small, camera.image_size, 0, 0, cv::INTER_AREA);
    const BoardView grid_view = detect_board(synthetic::linear_rgb_from_srgb8(small), grid, &camera);
    ASSERT_TRUE(grid_view.found()) << grid_view.problem;
    EXPECT_EQ(grid_view.markers_detected, 12);

    r = run_cli({"board", "--board", "chessboard", "--squares", "9x6", "--square-length", "0.025", "--margin", "0.01",
                 "-o", (dir / "chess.png").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_valid_pdf(dir / "chess.pdf", 245.0, 170.0);
    BoardSpec chess;
    chess.type = BoardType::Chessboard, chess.squares_x = 9, chess.squares_y = 6, chess.square_length = 0.025;
    const BoardView chess_view = detect_in_print(dir / "chess.png", chess, 600.0);
    ASSERT_TRUE(chess_view.found()) << chess_view.problem;
    EXPECT_EQ(chess_view.image_points.size(), 8u * 5u);
}

TEST(BoardCli, BadOptionsExitWithStatus2AndOneLineNamingTheValue) {
    const fs::path dir = scratch_directory("surfscatter_board_cli");
    const std::string out = (dir / "bad.png").string();
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases{
        {{"--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "--dpi", "0", "-o", out},
         "--dpi 0"},
        {{"--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "-o", (dir / "b.txt").string()},
         "b.txt"},
        {{"--squares", "10", "--square-length", "0.03", "--marker-length", "0.022", "-o", out}, "--squares '10'"},
        {{"--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "--margin", "-0.01", "-o", out},
         "--margin -0.01"},
        {{"--squares", "10x7", "--square-length", "1", "--marker-length", "0.5", "--dpi", "2000", "-o", out},
         "more than 30000 a side"},
        {{"--squares", "10x7", "--square-length", "0.001", "--marker-length", "0.0005", "--dpi", "100", "-o", out},
         "fewer than 8"},
        {{"--board", "chessboard", "--squares", "9x6", "--square-length", "0.025", "--marker-length", "0.01", "-o",
          out},
         "--marker-length"},
        {{"--squares", "200x10", "--square-length", "0.03", "--marker-length", "0.022", "--dictionary", "6X6_1000",
          "--dpi", "50", "-o", out},
         "more than a PDF page's 5080 mm a side"},
        {{"--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "--dpi", "nan", "-o", out},
         "--dpi nan"},
        {{"--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "-o",
          (dir / "no" / "such" / "b.png").string()},
         "folder " + (dir / "no" / "such").string() + " does not exist"},
    };
    for (const auto& [options, expected] : cases) {
        std::vector<std::string> args{"board"};
        args.insert(args.end(), options.begin(), options.end());
        const auto r = run_cli(args);
        EXPECT_EQ(r.exit_code, 2) << expected << ": " << r.err;
        EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    }
    EXPECT_FALSE(fs::exists(out));
}

// The committed example photographs (boards, chart, grey card) are what `board` and example-board-photos make today,
// sample for sample.
TEST(ExampleData, BoardPhotosAreRemadeByTheCommandsOfTheirReadme) {
    const fs::path dir = scratch_directory("surfscatter_example_photos");
    auto r = run_cli({"board", "--squares", "10x7", "--square-length", "0.03", "--marker-length", "0.022", "--dpi",
                      "100", "-o", (dir / "board.png").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string command = std::string(test::shell_quote(SURFSCATTER_EXAMPLE_BOARD_PHOTOS)) + " " +
                                test::shell_quote((dir / "board.png").string()) + " " +
                                test::shell_quote((dir / "photos").string()) + " >/dev/null";
    ASSERT_EQ(std::system(command.c_str()), 0);
    std::vector<std::string> names{"chart.jpg", "grey_card.jpg"};
    for (int i = 1; i <= 7; ++i) names.push_back("board" + std::to_string(i) + ".png");
    for (const std::string& name : names) {
        const io::Raster made = io::read_raster(dir / "photos" / name);
        const io::Raster committed = io::read_raster(kExampleData / "photos" / name);
        ASSERT_EQ(made.width, committed.width) << name;
        ASSERT_EQ(made.height, committed.height) << name;
        int largest = 0;
        for (std::size_t k = 0; k < made.samples.size(); ++k)
            largest = std::max(largest, std::abs(int(made.samples[k]) - int(committed.samples[k])));
        EXPECT_LE(largest, 1) << name;
    }
    EXPECT_EQ(read_whole_file((dir / "photos" / "views.json").string()),
              read_whole_file((kExampleData / "photos" / "views.json").string()));
}

// The example height maps are what the README's synth commands make (heights within float rounding: the .gsf holds
// 32-bit floats, and another CPU's FFT code may round differently).
void expect_remade(const std::vector<std::string>& options, const std::string& name) {
    const fs::path dir = scratch_directory("surfscatter_example_photos");
    std::vector<std::string> args{"surface", "synth"};
    args.insert(args.end(), options.begin(), options.end());
    args.push_back("-o");
    args.push_back((dir / name).string());
    const auto r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const heightmap::HeightMap made = heightmap::read_gsf(dir / name);
    const heightmap::HeightMap committed = heightmap::read_gsf(kExampleData / name);
    ASSERT_EQ(made.nx(), committed.nx());
    ASSERT_EQ(made.ny(), committed.ny());
    EXPECT_EQ(made.spacing_x(), committed.spacing_x());
    double largest = 0.0;
    for (std::size_t i = 0; i < made.size(); ++i)
        largest = std::max(largest, std::abs(made.heights()[i] - committed.heights()[i]));
    EXPECT_LT(largest, 1e-6) << name;  // um; the heights are about 0.05 um
}

TEST(ExampleData, TheHeightMapIsRemadeByTheCommandOfItsReadme) {
    expect_remade({"--model", "kc", "--sigma", "0.05", "--corr-length", "2", "--gamma", "3", "--size", "128",
                   "--spacing", "0.5", "--seed", "1", "--title", "surfscatter example: KC sigma 0.05 um, L 2 um, gamma 3"},
                  "kc_surface.gsf");
}

TEST(ExampleData, TheBrushedHeightMapIsRemadeByTheCommandOfItsReadme) {
    expect_remade({"--model", "kc", "--sigma", "0.05", "--corr-length", "4", "--corr-length-v", "1", "--lay-angle",
                   "30", "--gamma", "3", "--size", "128", "--spacing", "0.5", "--seed", "1", "--title",
                   "surfscatter example: brushed, KC sigma 0.05 um, LU 4 um, LV 1 um, lay angle 30 deg, gamma 3"},
                  "brushed_surface.gsf");
}

TEST(ExampleData, CalibrateAndPoseOnTheExamplePhotosRecoverTheTrueCamera) {
    const fs::path dir = scratch_directory("surfscatter_example_photos");
    std::vector<std::string> args{"calibrate"};
    for (int i = 1; i <= 7; ++i)
        args.push_back((kExampleData / "photos" / ("board" + std::to_string(i) + ".png")).string());
    for (const char* a : {"--board", "charuco", "--squares", "10x7", "--square-length", "0.03", "--marker-length",
                          "0.022", "-o"})
        args.push_back(a);
    args.push_back((dir / "camera.yml").string());
    auto r = run_cli(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CameraModel truth = read_camera(kExampleData / "photos" / "camera_true.yml");
    const CameraModel found = read_camera(dir / "camera.yml");
    EXPECT_NEAR(found.fx(), truth.fx(), 2.0);  // 0.3 %; its standard deviation is 0.3 px
    EXPECT_NEAR(found.fy(), truth.fy(), 2.0);
    EXPECT_NEAR(found.cx(), truth.cx(), 1.5);
    EXPECT_NEAR(found.cy(), truth.cy(), 1.5);
    EXPECT_NEAR(found.distortion[0], truth.distortion[0], 0.01);

    const nlohmann::json views =
        nlohmann::json::parse(read_whole_file((kExampleData / "photos" / "views.json").string()));
    for (int i : {1, 3, 6}) {
        const auto& view = views["views"][static_cast<std::size_t>(i - 1)];
        r = run_cli({"pose", (kExampleData / "photos" / view["image"].get<std::string>()).string(), "--camera",
                     (dir / "camera.yml").string(), "--board", "charuco", "--squares", "10x7", "--square-length",
                     "0.03", "--marker-length", "0.022", "-o", (dir / "pose.json").string()});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto pose = nlohmann::json::parse(read_whole_file((dir / "pose.json").string()));
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(pose["camera_position_m"][static_cast<std::size_t>(k)].get<double>(),
                        view["eye_m"][static_cast<std::size_t>(k)].get<double>(), 0.002)
                << view["image"] << " axis " << k;
    }
}

}  // namespace
}  // namespace surfscatter::photo
