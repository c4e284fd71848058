// End-to-end tests of `surfscatter fit-brdf`: the outputs and summary lines on the shipped example (GGX from
// statistics only, the fast model), and bad data: one line naming the row, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

using surfscatter::test::read_whole_file;
using surfscatter::test::run_cli;
using surfscatter::test::scratch_directory;

namespace {

const std::string kExample = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/fit_brdf_au.csv";
const std::string kHeader = "wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf\n";
const std::string kGood = "550,30,0,30,180,1.5\n550,30,0,35,180,0.5\n550,30,0,40,180,0.2\n";

void expect_bad_data(const std::string& text, const std::string& needle, const std::string& name = "bad.csv") {
    const auto dir = scratch_directory("surfscatter_cli_fit_brdf");
    const auto path = (dir / name).string();
    std::ofstream(path) << text;
    const auto r = run_cli({"fit-brdf", "--data", path, "--material", "Au", "--model", "ggx_stats", "-o",
                            (dir / "fitted").string()});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "fitted.json"));
}

}  // namespace

TEST(CliFitBrdf, WritesJsonCsvPlotAndSummary) {
    const auto dir = scratch_directory("surfscatter_cli_fit_brdf");
    const auto out = (dir / "fit").string();
    const auto r = run_cli({"fit-brdf", "--data", kExample, "--material", "Au", "--model", "ggx_stats", "--psd", "kc",
                            "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_GE(lines.size(), 3u);
    EXPECT_EQ(lines[0].rfind("ggx_stats: sigma_um", 0), 0u) << lines[0];
    EXPECT_NE(lines[1].find("the only model fitted"), std::string::npos) << lines[1];
    const std::string json = read_whole_file(out + ".json");
    for (const char* key : {"\"correlation\"", "\"worst_directions\"", "\"standard_error\"", "\"verdict\""})
        EXPECT_NE(json.find(key), std::string::npos) << key;
    EXPECT_EQ(read_whole_file(out + ".csv").rfind(
                  "wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf,ggx_stats_fit,ggx_stats_residual\n", 0),
              0u);
    EXPECT_GT(std::filesystem::file_size(out + "_residuals.png"), 10000u);
}

// An RGL file as data: one written by brdf export (small, coarse: --tolerance accepts its error), read at its sample
// nodes at the wavelengths asked for.
TEST(CliFitBrdf, ReadsAnRglFile) {
    const auto dir = scratch_directory("surfscatter_cli_fit_brdf");
    const auto file = (dir / "gold.bsdf").string();
    const auto e = run_cli({"brdf", "export", "--model", "ggx_stats", "--sigma", "0.1", "--corr-length", "1.5",
                            "--gamma", "3.5", "--material", "Au", "--format", "rgl-spectral", "--theta-i-count", "4",
                            "--sample-resolution", "12", "--ndf-resolution", "24", "--lambda-step", "80",
                            "--tolerance", "1e6", "-o", file});
    ASSERT_EQ(e.exit_code, 0) << e.err;
    const auto r = run_cli({"fit-brdf", "--data", file, "--material", "Au", "--model", "ggx_stats", "--wavelengths",
                            "500,600", "-o", (dir / "fit").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out.rfind("read ", 0), 0u) << r.out;
    EXPECT_NE(r.out.find("at 500,600 nm"), std::string::npos) << r.out;
    const auto outside = run_cli({"fit-brdf", "--data", file, "--material", "Au", "--model", "ggx_stats",
                                  "--wavelengths", "300", "-o", (dir / "fit2").string()});
    EXPECT_EQ(outside.exit_code, 2);
    EXPECT_NE(outside.err.find("wavelength 300 nm is outside the file"), std::string::npos) << outside.err;
}

TEST(CliFitBrdf, BadDataNamesTheRow) {
    expect_bad_data("wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,brdf\n550,30,0,30,1\n", "bad.csv:1: expected");
    expect_bad_data(kHeader + kGood + "550,30,0,45,180,-0.1\n", "bad.csv:5: brdf must be finite and >= 0");
    expect_bad_data(kHeader + kGood + "550,30,0,45,180,nan\n", "bad.csv:5: brdf must be finite");
    expect_bad_data(kHeader + kGood + "550,30,0,91,180,0.1\n", "bad.csv:5: theta_o_deg must be in [0, 90)");
    expect_bad_data(kHeader + "550,30,0,30,180,1.5\n550,30,0,30,180,1.4\n", "one direction");
    expect_bad_data(kHeader + kGood, "not a tensor file", "measured.bsdf");  // read as RGL by its extension
}

TEST(CliFitBrdf, BadOptionsAreErrors) {
    const auto dir = scratch_directory("surfscatter_cli_fit_brdf");
    for (const auto& [extra, needle] :
         std::vector<std::pair<std::vector<std::string>, std::string>>{
             {{"--fix", "gamma"}, "--fix must be NAME=VALUE"},
             {{"--fix", "roughness=2"}, "--fix roughness: not a parameter"},
             {{"--fix", "lay_angle_deg=10"}, "--fix lay_angle_deg applies to an anisotropic fit only (--anisotropic)"},
             {{"--psd", "gaussian", "--fix", "gamma=3"}, "--fix gamma applies to --psd kc only"},
             {{"--psd", "file"}, "--psd must be kc or gaussian"},
             {{"--model", "phong"}, "--model must be one of"},
             {{"--wavelengths", "550"}, "--wavelengths applies to RGL .bsdf data only"},
             {{"--profile", "x"}, "--profile must be"},
             {{"--profile", "s"}, "phi_o_deg must be 0 or 180 for profile data"},
             {{"--profile", "s", "--model", "two_scale"}, "two_scale has no 1-D form"},
             {{"--profile", "p", "--anisotropic"}, "--profile data are a cut through isotropic statistics: "
                                                   "--anisotropic does not apply"}}) {
        std::vector<std::string> args = {"fit-brdf", "--data", kExample, "--material", "Au", "-o",
                                         (dir / "opt").string()};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto r = run_cli(args);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    }
    const auto copy = (dir / "in").string();
    std::filesystem::copy_file(kExample, copy + ".csv", std::filesystem::copy_options::overwrite_existing);
    const auto r = run_cli({"fit-brdf", "--data", copy + ".csv", "--material", "Au", "-o", copy});
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_NE(r.err.find("-o's CSV " + copy + ".csv would replace the input --data " + copy + ".csv"), std::string::npos)
        << r.err;
}
