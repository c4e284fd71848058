// End-to-end tests of `surfscatter validity`'s map route: a height map file (the example KC map) and synthesised
// maps; the table's columns, the JSON, the PNGs; exit 2 where the Kirchhoff reference is outside its validity in
// every case; bad input refused in one line.
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

std::string out_prefix(const char* name) { return (scratch_directory("surfscatter_cli_validity_map") / name).string(); }

void expect_bad_input(const std::vector<std::string>& args, const std::string& needle) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

// The example KC map (128 x 128 pixels of 0.5 um): both model routes (measured PSD and KC fit) for every model, SSA
// ruled out (the map's k sigma is 0.6), the reference valid.
TEST(CliValidityMap, HeightMapFileWritesTheTableJsonAndPlots) {
    const auto out = out_prefix("file");
    const auto r = run_cli({"validity", "--surface-file", kMap, "--material", "perfect", "--wavelengths", "550",
                            "--theta-i", "0", "--bin-deg", "6", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("550 nm, theta_i 0 deg, phi_i 0 deg: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ruled out: ghs_ssa/measured"), std::string::npos) << r.out;
    const std::string csv = read_whole_file(out + ".csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "model,wavelength_nm,theta_i_deg,polarisation,median_rel_error,worst_rel_error,worst_theta_o_deg,"
              "directions_used,directions_excluded,reference_median_rel_stderr,model_energy,reference_energy,"
              "trusted,verdict,phi_i_deg,reference_valid");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 8);  // 4 models x (measured, file)
    EXPECT_NE(csv.find("\nghs/file,550,0,unpolarised,"), std::string::npos) << csv;
    const std::string json = read_whole_file(out + ".json");
    EXPECT_NE(json.find("\"reference_validity\""), std::string::npos);
    EXPECT_NE(json.find("\"route\":\"maps\""), std::string::npos);
    EXPECT_GT(std::filesystem::file_size(out + "_slices.png"), 1000u);
    EXPECT_GT(std::filesystem::file_size(out + "_error_map.png"), 1000u);
}

// A correlation length far under the wavelength (k l about 0.6): every verdict is marked, and the command exits 2
// after writing the table.
TEST(CliValidityMap, ReferenceOutsideItsValidityExitsTwo) {
    const auto out = out_prefix("invalid");
    const auto r = run_cli({"validity", "--psd", "gaussian", "--sigma", "0.005", "--corr-length", "0.05",
                            "--map-size-um", "4", "--map-pixels", "128", "--subarea-um", "1", "--material", "perfect",
                            "--wavelengths", "550", "--theta-i", "0", "-o", out});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("the Kirchhoff reference is outside its validity in every case"), std::string::npos) << r.err;
    EXPECT_NE(r.out.find("not concluded, the reference is not trusted here (Kirchhoff outside its validity: k l ="),
              std::string::npos)
        << r.out;
    const std::string csv = read_whole_file(out + ".csv");
    EXPECT_NE(csv.find(",0,0\n"), std::string::npos) << csv;  // phi_i 0, reference_valid 0
}

TEST(CliValidityMap, RefusesBadInput) {
    const auto out = out_prefix("bad");
    const std::vector<std::string> base{"validity", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0",
                                        "-o", out};
    const auto with = [&](std::vector<std::string> extra) {
        auto args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    expect_bad_input(with({"--surface-file", kMap, "--psd", "kc", "--sigma", "0.1", "--corr-length", "2", "--gamma",
                           "3"}),
                     "--surface-file is the surface");
    expect_bad_input(with({"--surface-file", kMap, "--polarisation", "s"}), "--polarisation: the map route is unpolarised");
    expect_bad_input(with({"--surface-file", kMap, "--realizations", "3"}),
                     "--realizations: a measured map (--surface-file) is one realization, got 3");
    expect_bad_input(with({"--surface-file", kMap, "--length-um", "12"}), "--length-um and --beam-width belong to");
    expect_bad_input(with({"--surface-file", kMap, "--form", "poly9"}), "--form");
    expect_bad_input(with({"--map-size-um", "16"}), "--map-size-um synthesises maps from --psd");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.02", "--corr-length", "2", "--gamma", "3", "--map-size-um",
                           "16", "--map-pixels", "4"}),
                     "--map-pixels must be in [8, 8192], got 4");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.02", "--corr-length", "2", "--gamma", "3", "--phi-i", "30",
                           "--length-um", "12", "--beam-width", "2", "--realizations", "4"}),
                     "belong to the map route");
    expect_bad_input(with({"--surface-file", kMap, "--max-theta-o", "95"}), "--max-theta-o must be in (0, 90)");
}
