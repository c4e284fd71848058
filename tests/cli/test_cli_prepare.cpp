// The one preparation of a map (heightmap/prepare.hpp) at the CLI: every command that reads a map takes the same
// options, says how the map was prepared, and refuses a preparation option where no map is prepared.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace fs = std::filesystem;
using surfscatter::test::run_cli;

namespace {

fs::path temp_dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_prepare"); }

// A small KC map with row offsets of a scanning instrument (a tenth of its rms per row).
std::string scanned_map() {
    const fs::path path = temp_dir() / "scanned.gsf";
    if (fs::exists(path)) return path.string();
    const std::size_t n = 128;
    surfscatter::heightmap::HeightMap map = surfscatter::surface::synthesize_surface(
        surfscatter::surface::KCorrelation(0.05, 1.0, 3.0), {n, n, 0.25}, 5);
    std::vector<double> h = map.heights();
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix) h[iy * n + ix] += 0.02 * std::sin(1.7 * double(iy * iy));
    surfscatter::heightmap::write_height_map(map.with_heights(std::move(h)), path);
    return path.string();
}

const std::string kExample = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";

TEST(CliPrepare, EveryMapReaderStatesThePreparation) {
    const auto info = run_cli({"surface", "info", scanned_map()});
    ASSERT_EQ(info.exit_code, 0) << info.err;
    EXPECT_NE(info.out.find("preparation = prepared: outliers keep"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("aligned"), std::string::npos) << "row offsets are found and removed: " << info.out;

    const auto brdf = run_cli({"brdf", "eval", "--model", "ghs", "--psd", "measured", "--surface", scanned_map(),
                               "--lambda-c", "8", "--material", "Au", "--wavelength", "550", "--theta-i", "30",
                               "--theta-o", "30", "--phi-o", "180"});
    ASSERT_EQ(brdf.exit_code, 0) << brdf.err;
    EXPECT_NE(brdf.err.find("L-filter lambda_c 8 um"), std::string::npos) << brdf.err;
    EXPECT_NE(brdf.err.find("the waviness (periods beyond lambda_c 8 um"), std::string::npos) << brdf.err;
}

TEST(CliPrepare, TwoScaleTakesTheWavinessIntoItsMacroSlopes) {
    const auto brdf = run_cli({"brdf", "eval", "--model", "two_scale", "--psd", "measured", "--surface", kExample,
                               "--lambda-c", "10", "--material", "Au", "--wavelength", "550", "--theta-i", "30",
                               "--theta-o", "30", "--phi-o", "180"});
    ASSERT_EQ(brdf.exit_code, 0) << brdf.err;
    EXPECT_NE(brdf.err.find("is added to the macro NDF's slopes"), std::string::npos) << brdf.err;
}

TEST(CliPrepare, BadValuesNameTheOption) {
    struct Case {
        std::vector<std::string> args;
        std::string message;
    };
    const std::vector<Case> cases = {
        {{"surface", "info", kExample, "--lambda-c", "bogus"}, "--lambda-c must be a nesting index"},
        {{"surface", "info", kExample, "--lambda-c", "-3"}, "--lambda-c must be a nesting index"},
        {{"surface", "info", kExample, "--lambda-s", "auto"}, "--lambda-s must be a nesting index"},
        {{"surface", "info", kExample, "--row-alignment", "sideways"}, "--row-alignment"},
        {{"surface", "fit", kExample, "--lambda-s", "20", "--lambda-c", "10"}, "must be longer than lambda_s"},
        {{"reference", "kirchhoff", "--surface", kExample, "--lambda-c", "nan", "--material", "Au", "--wavelength",
          "550", "--theta-i", "0", "-o", (temp_dir() / "k.csv").string()},
         "--lambda-c must be a nesting index"},
    };
    for (const Case& c : cases) {
        const auto r = run_cli(c.args);
        EXPECT_EQ(r.exit_code, 2) << c.args[1] << " " << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_TRUE(r.out.empty()) << r.out;
    }
}

// An option that prepares a map is an error where there is no map to prepare, never ignored.
TEST(CliPrepare, PreparationOptionsWithoutAMapAreErrors) {
    const auto brdf = run_cli({"brdf", "eval", "--model", "ghs", "--sigma", "0.05", "--corr-length", "2", "--gamma",
                               "3", "--lambda-c", "10", "--material", "Au", "--wavelength", "550", "--theta-i", "30",
                               "--theta-o", "30"});
    EXPECT_EQ(brdf.exit_code, 2);
    EXPECT_NE(brdf.err.find("--lambda-c does not apply"), std::string::npos) << brdf.err;
    const auto profiles = run_cli({"validity", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma", "3",
                                   "--material", "perfect", "--wavelengths", "550", "--theta-i", "0", "--length-um",
                                   "24", "--beam-width", "4", "--realizations", "2", "--form", "poly2", "-o",
                                   (temp_dir() / "v").string()});
    EXPECT_EQ(profiles.exit_code, 2);
    EXPECT_NE(profiles.err.find("--form does not apply to the profiles route (--length-um): it applies to a measured map"), std::string::npos) << profiles.err;
    const auto synthesised = run_cli({"validity", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1", "--gamma",
                                      "3", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0",
                                      "--map-size-um", "16", "--row-alignment", "none", "-o",
                                      (temp_dir() / "m").string()});
    EXPECT_EQ(synthesised.exit_code, 2);
    EXPECT_NE(synthesised.err.find("--row-alignment does not apply to synthesised maps"), std::string::npos) << synthesised.err;
}

}  // namespace
