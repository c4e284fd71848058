// End-to-end tests of `surfscatter reference exact-1d`: the CSV it writes (a flat perfect conductor reflects 1, a
// flat silver profile what `surfscatter fresnel` prints), the statistical mode's columns, and bad input (exit 2,
// one line naming the value).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_runner.hpp"
#include "surfscatter/core/resources.hpp"
#include "spectrum/test_data.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/synthesis.hpp"

using surfscatter::test::read_whole_file;
using surfscatter::test::run_cli;
using surfscatter::test::scratch_directory;
using surfscatter::test::write_temp_file;

namespace {

// A flat profile from -half to half um.
std::string flat_profile(double half, double step) {
    std::string text = "x_um,h_um\n";
    for (double x = -half; x <= half + 1e-9; x += step) text += fmt::format("{:.6f},0\n", x);
    return text;
}

// Integral of intensity_per_rad over theta_o (degrees converted), and the row count.
double integrate(const std::string& csv, std::size_t& rows) {
    double sum = 0;
    rows = 0;
    std::size_t start = csv.find('\n') + 1;
    while (start < csv.size()) {
        const std::size_t end = csv.find('\n', start);
        double theta = 0, value = 0;
        if (std::sscanf(csv.c_str() + start, "%lf,%lf", &theta, &value) == 2) {
            sum += value * (std::abs(theta) == 90 ? 0.5 : 1.0) * 0.1 * M_PI / 180;
            ++rows;
        }
        start = end + 1;
    }
    return sum;
}

void expect_bad_input(const std::vector<std::string>& args, const std::string& needle) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

TEST(CliReference, FlatProfilesReflectAsFresnelSays) {
    const std::string profile = write_temp_file(flat_profile(15, 0.05), ".csv");
    const auto out = (scratch_directory("surfscatter_cli_reference") / "flat.csv").string();
    auto r = run_cli({"reference", "exact-1d", "--profile", profile, "--material", "perfect", "--wavelength", "550",
                      "--theta-i", "30", "--polarisation", "s", "--beam-width", "5", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::string csv = read_whole_file(out);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "theta_o_deg,intensity_per_rad");
    std::size_t rows = 0;
    EXPECT_NEAR(integrate(csv, rows), 1.0, 1e-5);
    EXPECT_EQ(rows, 1801u);  // -90 to 90 every 0.1 deg
    r = run_cli({"reference", "exact-1d", "--profile", profile, "--material", "Ag", "--wavelength", "550",
                 "--theta-i", "30", "--polarisation", "p", "--beam-width", "5", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto fresnel = run_cli({"fresnel", "--material", "Ag", "--wavelength", "550", "--theta", "30",
                                  "--polarization", "p"});
    ASSERT_EQ(fresnel.exit_code, 0) << fresnel.err;
    double theta = 0, reflectance = 0;
    ASSERT_EQ(std::sscanf(fresnel.out_lines().at(1).c_str(), "%lf,%lf", &theta, &reflectance), 2);
    EXPECT_NEAR(integrate(read_whole_file(out), rows), reflectance, 1e-3);
}

TEST(CliReference, StatisticalModeWritesCoherentAndIncoherentParts) {
    const auto out = (scratch_directory("surfscatter_cli_reference") / "stat.csv").string();
    const auto r = run_cli({"reference", "exact-1d", "--psd", "kc", "--sigma", "0.02", "--corr-length", "1",
                            "--gamma", "3", "--length-um", "30", "--realizations", "2", "--seed", "4", "--material",
                            "perfect", "--wavelength", "1000", "--theta-i", "10", "--polarisation", "s",
                            "--beam-width", "5", "--threads", "2", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = read_whole_file(out);
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "theta_o_deg,intensity_per_rad,coherent_per_rad,coherent_stderr_per_rad,incoherent_per_rad,"
              "incoherent_stderr_per_rad");
    std::size_t rows = 0;
    EXPECT_NEAR(integrate(csv, rows), 1.0, 2e-3);
    EXPECT_EQ(rows, 1801u);
}

TEST(CliReference, BadInputIsOneLine) {
    const std::string profile = write_temp_file(flat_profile(15, 0.05), ".csv");
    const std::vector<std::string> base = {"reference", "exact-1d", "--material", "perfect", "--wavelength", "550",
                                           "--polarisation", "s", "-o", "/tmp/surfscatter_ref_unused.csv"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    expect_bad_input(with({"--profile", profile, "--theta-i", "90", "--beam-width", "5"}), "--theta-i must be in [0, 90)");
    expect_bad_input(with({"--profile", profile, "--theta-i", "10", "--beam-width", "8"}),
                     "does not hold the beam");
    expect_bad_input(with({"--profile", profile, "--theta-i", "10", "--beam-width", "0.5"}), "too narrow");
    expect_bad_input(with({"--profile", profile, "--theta-i", "10", "--beam-width", "5", "--psd", "kc"}),
                     "--profile and --psd exclude each other");
    expect_bad_input(with({"--theta-i", "10", "--beam-width", "5"}), "give --profile");
    expect_bad_input(with({"--profile", profile, "--theta-i", "10", "--beam-width", "5", "--realizations", "3"}),
                     "--realizations does not apply to one profile (--profile)");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.1", "--corr-length", "1", "--length-um", "30",
                           "--realizations", "3", "--theta-i", "10", "--beam-width", "5"}),
                     "--gamma is required for --psd kc");
    expect_bad_input(with({"--profile", write_temp_file("x_um,h_um\n0,0\n1,0\n3,0\n4,0\n", ".csv"), "--theta-i", "10",
                           "--beam-width", "5"}),
                     ":4: x = 3 um breaks the uniform step");
    expect_bad_input(with({"--profile", profile, "--theta-i", "10", "--beam-width", "5", "--points-per-wavelength",
                           "2"}),
                     "--points-per-wavelength must be between 4 and 1000, got 2");
}

// A profile whose solve needs twice the memory available now (about 5 KB per node at 550 nm; 11 samples far apart,
// splined onto the nodes): refused before the solve's buffers exist, exit status 2, in one line naming the options
// that set the node count.
TEST(CliReference, MoreNodesThanMemoryIsOneLine) {
    const double available = static_cast<double>(surfscatter::available_memory_bytes());
    const double nodes = std::min(2.0 * available / 4500.0, 0.99e7);  // within kMaxExact1dNodes
    if (4500.0 * nodes < 1.5 * available) GTEST_SKIP() << "no profile within kMaxExact1dNodes exceeds the memory";
    const double spacing = nodes / 10.0 * 0.055;  // 10 intervals of nodes / 10 nodes each at 550 nm
    std::string csv = "x_um,h_um\n";
    for (int j = -5; j <= 5; ++j) csv += fmt::format("{:.17g},{}\n", j * spacing, j % 2 == 0 ? 0.0 : 0.1);
    expect_bad_input({"reference", "exact-1d", "--profile", write_temp_file(csv, ".csv"), "--material", "perfect",
                      "--wavelength", "550", "--theta-i", "0", "--polarisation", "s", "--beam-width", "10", "-o",
                      "/tmp/surfscatter_ref_unused.csv"},
                     "use fewer --points-per-wavelength (now 10), a shorter profile in --profile (now ");
}

// reference models-1d: the CSV on exact-1d's grid (GHS's coherent fraction plus its lobe is 1 for a perfect
// conductor), the JSON with the coherent fractions, the PNG, and options the chosen model does not use refused.
TEST(CliReference, Models1dWritesTheModelsOnTheExactGrid) {
    const auto out = (scratch_directory("surfscatter_cli_reference") / "models.csv").string();
    const auto r = run_cli({"reference", "models-1d", "--psd", "kc", "--sigma", "0.05", "--corr-length", "2",
                            "--gamma", "3", "--material", "perfect", "--wavelength", "550", "--theta-i", "30",
                            "--polarisation", "s", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string csv = read_whole_file(out);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "theta_o_deg,ghs_per_rad,ghs_ssa_per_rad,kirchhoff_per_rad");
    std::size_t rows = 0;
    const double lobe = integrate(csv, rows);  // the first model's column
    EXPECT_EQ(rows, 1801u);
    const std::string json = read_whole_file(out.substr(0, out.size() - 4) + ".json");
    const auto at = json.find("\"coherent\":", json.find("\"ghs\""));
    ASSERT_NE(at, std::string::npos) << json;
    const double coherent = std::stod(json.substr(at + 11));
    const auto sigma_at = json.find("\"sigma_um\":", at);
    ASSERT_NE(sigma_at, std::string::npos) << json;
    const double sigma_rel = std::stod(json.substr(sigma_at + 11)), k = 2 * M_PI / 0.55;
    EXPECT_LT(sigma_rel, 0.05);  // the 1-D relevant roughness: part of the PSD lies beyond the visible interval
    EXPECT_NEAR(coherent, std::exp(-std::pow(2 * k * sigma_rel * std::cos(M_PI / 6), 2)), 1e-12);
    EXPECT_NEAR(coherent + lobe, 1.0, 1e-4);
    EXPECT_NE(r.out.find("ghs: coherent fraction"), std::string::npos) << r.out;
    EXPECT_GT(std::filesystem::file_size(out.substr(0, out.size() - 4) + ".png"), 1000u);

    const std::vector<std::string> surface{"reference", "models-1d", "--psd", "gaussian", "--sigma", "0.05",
                                           "--corr-length", "2", "--material", "perfect", "--wavelength", "550",
                                           "--polarisation", "s", "-o", out};
    const auto with = [&](std::vector<std::string> extra) {
        auto args = surface;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    expect_bad_input(with({"--theta-i", "90"}), "--theta-i must be in [0, 90) degrees, got 90");
    expect_bad_input(with({"--theta-i", "10", "--model", "kirchhoff", "--fresnel", "rr"}),
                     "--fresnel is not used by kirchhoff");
    expect_bad_input(with({"--theta-i", "10", "--model", "ghs", "--ssa-form", "strict"}),
                     "--ssa-form is used by ghs_ssa only");
    expect_bad_input(with({"--theta-i", "10", "--model", "ggx"}), "--model must be one of ghs | ghs_ssa | kirchhoff");
    expect_bad_input(with({"--theta-i", "10", "--gamma", "3"}), "--gamma applies to --psd kc only");
    expect_bad_input({"reference", "models-1d", "--material", "perfect", "--wavelength", "550", "--theta-i", "10",
                      "--polarisation", "s", "-o", out},
                     "models-1d needs the surface");
}

// validity: the table's columns and rows, the JSON and the two PNGs; a reference too noisy to conclude anything
// (4 realizations) is said so and exits 2 after writing what it has; bad input refused in one line.
TEST(CliReference, ValidityWritesTheTableAndRefusesAnUnresolvedReference) {
    const auto out = (scratch_directory("surfscatter_cli_reference") / "validity").string();
    const std::vector<std::string> base{"validity", "--psd", "kc", "--sigma", "0.01", "--corr-length", "1",
                                        "--gamma", "3", "--material", "perfect", "--wavelengths", "550",
                                        "--length-um", "12", "--beam-width", "2", "-o", out};
    const auto with = [&](std::vector<std::string> extra) {
        auto args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    const auto r = run_cli(with({"--theta-i", "0,40", "--realizations", "4"}));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("nothing can be concluded in 4 of 4 cases, no model is ruled out there: the reference is "
                         "outside its validity (550 nm, theta_i 0 deg, s: "),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("550 nm, theta_i 40 deg, p: nothing can be concluded and no model is ruled out: the "
                         "reference is outside its validity ("),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("; ruled out:"), std::string::npos) << r.out;
    const std::string csv = read_whole_file(out + ".csv");
    EXPECT_EQ(csv.substr(0, csv.find('\n')),
              "model,wavelength_nm,theta_i_deg,polarisation,median_rel_error,worst_rel_error,worst_theta_o_deg,"
              "directions_used,directions_excluded,reference_median_rel_stderr,model_energy,reference_energy,"
              "trusted,verdict");
    // (ghs, ghs_ssa, kirchhoff, two_scale; gamma 3: no ggx_stats) x incidences x polarisations
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 4 * 2 * 2);
    EXPECT_NE(csv.find("\ntwo_scale,550,40,p,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("\nkirchhoff,550,40,p,"), std::string::npos) << csv;
    EXPECT_NE(read_whole_file(out + ".json").find("\"verdict\""), std::string::npos);
    EXPECT_GT(std::filesystem::file_size(out + "_slices.png"), 1000u);
    EXPECT_GT(std::filesystem::file_size(out + "_error_map.png"), 1000u);

    expect_bad_input(with({"--theta-i", "0,90", "--realizations", "4"}), "theta_i must be in [0, 90) degrees, got 90");
    expect_bad_input(with({"--theta-i", "0", "--realizations", "1"}), "--realizations must be at least 2, got 1");
    expect_bad_input(with({"--theta-i", "0", "--realizations", "4", "--target-stderr", "5"}),
                     "--realizations and --target-stderr: give one");
    expect_bad_input(with({"--theta-i", "0", "--target-stderr", "0"}), "--target-stderr must be in (0, 100) percent");
    expect_bad_input(with({"--theta-i", "0", "--realizations", "4", "--max-realizations", "9"}),
                     "--max-realizations caps --target-stderr's profiles");
    expect_bad_input(with({"--theta-i", "0", "--realizations", "4", "--tolerance", "2"}),
                     "--tolerance must be in (0, 1), got 2");
    expect_bad_input({"validity", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0", "--length-um",
                      "12", "--beam-width", "2", "--realizations", "4", "-o", out},
                     "validity needs the surface");
}

// validity's map route: a height map file (the example KC map) and synthesised maps; the table's columns, the
// JSON, the PNGs; exit 2 where the Kirchhoff reference is outside its validity in every case; bad input.
namespace {

const std::string kExampleMap = std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf";

std::string map_out(const char* name) { return (scratch_directory("surfscatter_cli_validity_map") / name).string(); }

}  // namespace

// The example KC map (128 x 128 pixels of 0.5 um): both model routes (measured PSD and KC fit) for every model, SSA
// ruled out (the map's k sigma is 0.6), the reference valid.
TEST(CliValidityMap, HeightMapFileWritesTheTableJsonAndPlots) {
    const auto out = map_out("file");
    const auto r = run_cli({"validity", "--surface-file", kExampleMap, "--material", "perfect", "--wavelengths", "550",
                            "--theta-i", "0", "--bin-deg", "12", "-o", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("550 nm, theta_i 0 deg, phi_i 0 deg: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ruled out: ghs_ssa/file"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("ghs_ssa/measured ("), std::string::npos) << r.out;
    // 6 deg bins leave the reference 14 % noise, above the tolerance: nothing concluded, nothing ruled out, exit 2.
    const auto noisy = run_cli({"validity", "--surface-file", kExampleMap, "--material", "perfect", "--wavelengths",
                                "550", "--theta-i", "0", "--bin-deg", "6", "-o", out + "_noisy"});
    EXPECT_EQ(noisy.exit_code, 2) << noisy.err;
    EXPECT_NE(noisy.err.find("the reference's median standard error 14.3 % exceeds the tolerance 10 %"),
              std::string::npos)
        << noisy.err;
    EXPECT_EQ(noisy.out.find("; ruled out:"), std::string::npos) << noisy.out;
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
    const auto out = map_out("invalid");
    const auto r = run_cli({"validity", "--psd", "gaussian", "--sigma", "0.005", "--corr-length", "0.05",
                            "--map-size-um", "4", "--map-pixels", "128", "--subarea-um", "1", "--material", "perfect",
                            "--wavelengths", "550", "--theta-i", "0", "-o", out});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("nothing can be concluded in 1 of 1 cases, no model is ruled out there: the reference is "
                         "outside its validity (550 nm, theta_i 0 deg, phi_i 0 deg: Kirchhoff outside its validity"),
              std::string::npos)
        << r.err;
    EXPECT_NE(r.out.find("nothing can be concluded and no model is ruled out: the reference is outside its validity "
                         "(Kirchhoff outside its validity: k l ="),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("; ruled out:"), std::string::npos) << r.out;
    const std::string csv = read_whole_file(out + ".csv");
    EXPECT_NE(csv.find(",0,0\n"), std::string::npos) << csv;  // phi_i 0, reference_valid 0
}

// A smooth KC map (sigma 5 nm, L 2 um, 128 x 128 pixels of 0.5 um) with 8 spikes of 0.1 um: kept, they hold most of
// its pixel-scale roughness and the command writes its outputs and exits 2 saying so; filled, it runs and says what it
// filled (and exits 2 for another reason: its sub-areas do not resolve the smooth map's lobe). reference kirchhoff and
// brdf say the same.
TEST(CliValidityMap, DominantOutliersExitTwoUnlessFilled) {
    const auto clean = surfscatter::surface::synthesize_surface(surfscatter::surface::KCorrelation(0.005, 2.0, 3.0),
                                                                {128, 128, 0.5}, 7);
    std::vector<double> h = clean.heights();
    for (std::size_t k = 0; k < 8; ++k) h[(9 + 13 * k) * clean.nx() + 7 + 14 * k] += k % 2 ? 0.1 : -0.1;
    const std::string spiked = map_out("spiked.gsf");
    surfscatter::heightmap::write_height_map(clean.with_heights(h), spiked);
    const std::vector<std::string> args{"validity", "--surface-file", spiked, "--material", "perfect", "--wavelengths",
                                        "550", "--theta-i", "0", "--bin-deg", "12", "-o", map_out("spiked")};
    const auto kept = run_cli(args);
    EXPECT_EQ(kept.exit_code, 2) << kept.err;
    EXPECT_NE(kept.err.find("nothing can be trusted: "), std::string::npos) << kept.err;
    EXPECT_NE(kept.err.find("8 points in 8 spots stand out"), std::string::npos) << kept.err;
    EXPECT_NE(kept.err.find("outliers fill replaces them"), std::string::npos) << kept.err;
    EXPECT_TRUE(std::filesystem::exists(map_out("spiked") + ".json"));  // written before the refusal
    auto fill_args = args;
    fill_args.insert(fill_args.end(), {"--outliers", "fill"});
    const auto filled = run_cli(fill_args);
    // Filled, the outliers no longer stop it; the smooth map's lobe is too narrow for its sub-areas, which the
    // verdict and the exit status say instead.
    EXPECT_EQ(filled.exit_code, 2) << filled.err;
    EXPECT_EQ(filled.err.find("nothing can be trusted: "), std::string::npos) << filled.err;
    EXPECT_NE(filled.err.find("too small to resolve it"), std::string::npos) << filled.err;
    EXPECT_NE(filled.err.find("8 points in 8 spots stand out"), std::string::npos) << filled.err;
    EXPECT_NE(filled.err.find("filled from their neighbours"), std::string::npos) << filled.err;
    EXPECT_NE(read_whole_file(map_out("spiked") + ".json").find("\"policy\":\"fill\""), std::string::npos);

    const auto kirchhoff = run_cli({"reference", "kirchhoff", "--surface", spiked, "--material", "perfect",
                                    "--wavelength", "550", "--theta-i", "0", "--outliers", "fill", "-o",
                                    map_out("spiked_kirchhoff.csv")});
    ASSERT_EQ(kirchhoff.exit_code, 0) << kirchhoff.err;
    EXPECT_NE(kirchhoff.err.find("note: " + spiked + ": 8 points"), std::string::npos) << kirchhoff.err;
    const auto brdf = run_cli({"brdf", "eval", "--model", "ghs", "--surface", spiked, "--psd", "measured",
                               "--material", "perfect", "--wavelength", "550", "--theta-i", "0", "--theta-o", "10"});
    ASSERT_EQ(brdf.exit_code, 0) << brdf.err;
    EXPECT_NE(brdf.err.find("warning: " + spiked + ": 8 points"), std::string::npos) << brdf.err;
    expect_bad_input({"brdf", "eval", "--model", "ghs", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3",
                      "--material", "perfect", "--wavelength", "550", "--theta-i", "0", "--theta-o", "10",
                      "--outliers", "fill"},
                     "--outliers does not apply");
    expect_bad_input({"reference", "kirchhoff", "--surface", spiked, "--material", "perfect", "--wavelength", "550",
                      "--theta-i", "0", "--outliers", "drop", "-o", map_out("bad.csv")},
                     "--outliers: outliers must be keep or fill, got 'drop'");
}

TEST(CliValidityMap, RefusesBadInput) {
    const auto out = map_out("bad");
    const std::vector<std::string> base{"validity", "--material", "perfect", "--wavelengths", "550", "--theta-i", "0",
                                        "-o", out};
    const auto with = [&](std::vector<std::string> extra) {
        auto args = base;
        args.insert(args.end(), extra.begin(), extra.end());
        return args;
    };
    expect_bad_input(with({"--surface-file", kExampleMap, "--psd", "kc", "--sigma", "0.1", "--corr-length", "2", "--gamma",
                           "3"}),
                     "--psd does not apply to a measured map (--surface-file)");
    expect_bad_input(with({"--surface-file", kExampleMap, "--map-size-um", "16"}), "--surface-file is the surface");
    expect_bad_input(with({"--surface-file", kExampleMap, "--polarisation", "s"}),
                     "--polarisation does not apply to a measured map (--surface-file)");
    expect_bad_input(with({"--surface-file", kExampleMap, "--realizations", "3"}),
                     "--realizations does not apply to a measured map (--surface-file)");
    expect_bad_input(with({"--surface-file", kExampleMap, "--length-um", "12"}),
                     "--length-um does not apply to a measured map (--surface-file): it applies to the profiles route");
    expect_bad_input(with({"--surface-file", kExampleMap, "--form", "poly9"}), "--form");
    expect_bad_input(with({"--map-size-um", "16"}), "--map-size-um synthesises maps from --psd");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.02", "--corr-length", "2", "--gamma", "3", "--map-size-um",
                           "16", "--map-pixels", "4"}),
                     "--map-pixels must be in [8, 8192], got 4");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.02", "--corr-length", "2", "--gamma", "3", "--phi-i", "30",
                           "--length-um", "12", "--beam-width", "2", "--realizations", "4"}),
                     "--phi-i does not apply to the profiles route (--length-um)");
    expect_bad_input(with({"--surface-file", kExampleMap, "--max-theta-o", "95"}), "--max-theta-o must be in (0, 90)");
    expect_bad_input(with({"--psd", "kc", "--sigma", "0.02", "--corr-length", "2", "--gamma", "3", "--map-size-um",
                           "16", "--outliers", "fill"}),
                     "--outliers does not apply to synthesised maps (--map-size-um): it applies to a measured map");
}
