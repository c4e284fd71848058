// End-to-end tests of `surfscatter reference kirchhoff` on the example KC map: the CSV's columns and summary, the
// PNG, and bad input (exit 2, one line naming the value).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"

using surfscatter::test::read_whole_file;
using surfscatter::test::run_cli;
using surfscatter::test::scratch_directory;

namespace {

const std::string kMap = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";

void expect_bad_input(const std::vector<std::string>& extra, const std::string& needle) {
    std::vector<std::string> args = {"reference", "kirchhoff", "--surface", kMap, "--material", "perfect",
                                     "--wavelength", "550", "--theta-i", "30", "-o",
                                     (scratch_directory("surfscatter_cli_kirchhoff") / "bad.csv").string()};
    for (std::size_t j = 0; j + 1 < extra.size(); j += 2) {
        const auto at = std::find(args.begin(), args.end(), extra[j]);
        if (at != args.end()) *(at + 1) = extra[j + 1];
        else args.insert(args.end(), {extra[j], extra[j + 1]});
    }
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

TEST(CliReferenceKirchhoff, WritesTheLatticeAndAPlot) {
    const auto dir = scratch_directory("surfscatter_cli_kirchhoff");
    const auto csv = (dir / "k.csv").string(), png = (dir / "k.png").string();
    const auto r = run_cli({"reference", "kirchhoff", "--surface", kMap, "--material", "Au", "--wavelength", "550",
                            "--theta-i", "30", "--phi-i", "10", "-o", csv, "--plot", png});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string text = read_whole_file(csv);
    EXPECT_EQ(text.substr(0, text.find('\n')),
              "theta_o_deg,phi_o_deg,brdf_per_sr,standard_error_per_sr,coherent_per_sr");
    EXPECT_GT(std::count(text.begin(), text.end(), '\n'), 500);
    EXPECT_NE(r.out.find("subareas = 16\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("albedo = 0.7"), std::string::npos) << r.out;  // gold's 0.75, a little lost beyond Nyquist
    // 0.5 um pixels resolve |o + i| < 0.55 only at 550 nm: said on stderr.
    EXPECT_NE(r.err.find("warning: the pixel (0.5 x 0.5 um) resolves"), std::string::npos) << r.err;
    EXPECT_GT(std::filesystem::file_size(png), 10000u);
}

TEST(CliReferenceKirchhoff, BadInputIsOneLine) {
    expect_bad_input({"--theta-i", "95"}, "--theta-i must be in [0, 90) degrees, got 95");
    expect_bad_input({"--wavelength", "-1"}, "--wavelength");
    expect_bad_input({"--subarea-um", "4"}, "--subarea-um 4 um is 8 pixels of 0.5 um along x: at least 16");
    expect_bad_input({"--subarea-um", "40"}, "at least 2 are needed");
    expect_bad_input({"--wavelength", "40"}, "sampling too coarse for 40 nm");
    expect_bad_input({"--form", "cubic"}, "--form");
    expect_bad_input({"--max-theta-o", "90"}, "--max-theta-o must be in (0, 90) degrees, got 90");
    expect_bad_input({"--surface", "/nonexistent/map.gsf"}, "/nonexistent/map.gsf");
}
