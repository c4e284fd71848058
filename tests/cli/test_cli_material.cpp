// End-to-end tests of `surfscatter ior`, `fresnel` and `metals`: CSV output values and exit status 2 on bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <complex>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"
#include "spectrum/test_data.hpp"
#include "surfscatter/material/refractive_index.hpp"

using surfscatter::test::run_cli;
using surfscatter::test::shared_data;
using surfscatter::test::write_temp_file;

namespace {

// The single-line error contract: exit 2, nothing on stdout, one line on stderr containing `needle`.
void expect_bad_input(std::initializer_list<std::string> args, const std::string& needle) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace

TEST(CliIor, PrintsBuiltInLorentzDrude) {
    const auto r = run_cli({"ior", "--material", "Au", "--wavelength", "400,500,600"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "wavelength_nm,n,k");
    // Against the LD evaluation in optical_constants/rakic1998_ld/gold.csv (6 decimals).
    double lambda, n, k;
    ASSERT_EQ(std::sscanf(lines[2].c_str(), "%lf,%lf,%lf", &lambda, &n, &k), 3);
    EXPECT_EQ(lambda, 500.0);
    int matched = 0;
    for (const auto& row : surfscatter::test::read_shared_csv("optical_constants/rakic1998_ld/gold.csv")) {
        if (row[0] != 500.0) continue;
        EXPECT_NEAR(n, row[1], 1e-6);
        EXPECT_NEAR(k, row[2], 1e-6);
        ++matched;
    }
    EXPECT_EQ(matched, 1);
}

TEST(CliIor, ReadsYamlAndCsvFiles) {
    auto r = run_cli({"ior", "--material", shared_data("refractiveindex/SiO2_Malitson.yml"), "--wavelength", "587.5618"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    double lambda, n, k;
    ASSERT_EQ(std::sscanf(r.out_lines().at(1).c_str(), "%lf,%lf,%lf", &lambda, &n, &k), 3);
    EXPECT_NEAR(n, 1.45846, 2e-5);
    EXPECT_EQ(k, 0.0);
    r = run_cli({"ior", "--material", shared_data("optical_constants/gold.csv"), "--wavelength", "354.2"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.out_lines().at(1), "354.2,1.5,1.866");
}

TEST(CliIor, BadInputExitsWith2) {
    expect_bad_input({"ior", "--material", "Unobtainium", "--wavelength", "500"}, "unknown material 'Unobtainium'");
    expect_bad_input({"ior", "--material", "Au", "--wavelength", "100"}, "wavelength 100 nm is outside the range");
    expect_bad_input({"ior", "--material", shared_data("optical_constants/gold.csv"), "--wavelength", "1000"},
                     "outside the range 354.2-892 nm");
    expect_bad_input({"ior", "--material", "Au", "--wavelength", "0"}, "--wavelength must be positive");
    expect_bad_input({"ior", "--material", "Au", "--wavelength", "nan"}, "--wavelength");
    expect_bad_input({"ior", "--material", "Au", "--wavelength", "abc"}, "abc");
    expect_bad_input({"ior", "--material", "/nonexistent/x.yml", "--wavelength", "500"}, "/nonexistent/x.yml");
    const std::string bad = write_temp_file("wavelength_nm,n,k\n400,1,2\n500,oops,2\n", ".csv");
    expect_bad_input({"ior", "--material", bad, "--wavelength", "450"}, bad + ":3:");
    std::remove(bad.c_str());
    std::filesystem::remove(bad);
}

TEST(CliFresnel, NormalIncidenceAndPolarisations) {
    auto r = run_cli({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "0,45,80"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "theta_deg,R");
    double theta, reflectance;
    ASSERT_EQ(std::sscanf(lines[1].c_str(), "%lf,%lf", &theta, &reflectance), 2);
    const std::complex<double> eta = surfscatter::material::load_refractive_index("Au")->at(550);
    EXPECT_NEAR(reflectance, std::norm((eta - 1.0) / (eta + 1.0)), 1e-8);
    // s rises and p dips with the angle; unpolarised is their mean.
    double rs, rp, ru;
    r = run_cli({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "80", "--polarization", "s"});
    ASSERT_EQ(std::sscanf(r.out_lines().at(1).c_str(), "%lf,%lf", &theta, &rs), 2);
    r = run_cli({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "80", "--polarization", "p"});
    ASSERT_EQ(std::sscanf(r.out_lines().at(1).c_str(), "%lf,%lf", &theta, &rp), 2);
    ASSERT_EQ(std::sscanf(lines[3].c_str(), "%lf,%lf", &theta, &ru), 2);
    EXPECT_GT(rs, reflectance);
    EXPECT_LT(rp, reflectance);
    EXPECT_NEAR(ru, 0.5 * (rs + rp), 1e-8);
    r = run_cli({"fresnel", "--material", "perfect", "--wavelength", "550", "--theta", "30"});
    EXPECT_EQ(r.out_lines().at(1), "30,1");
}

TEST(CliFresnel, BadInputExitsWith2) {
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "90"}, "--theta must be in [0, 90)");
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "-1"}, "--theta must be in [0, 90)");
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "nan"}, "--theta");
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "-550", "--theta", "0"}, "--wavelength must be positive");
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "5000000", "--theta", "0"}, "outside the range");
    expect_bad_input({"fresnel", "--material", "Gold", "--wavelength", "550", "--theta", "0"}, "unknown material 'Gold'");
    expect_bad_input({"fresnel", "--material", "Au", "--wavelength", "550", "--theta", "0", "--polarization", "q"}, "q");
}

TEST(CliMetals, WritesReflectanceAndSwatchData) {
    const auto dir = std::filesystem::temp_directory_path() / "surfscatter_cli_metals";
    std::filesystem::remove_all(dir);
    const auto r = run_cli({"metals", "--out", dir.string(), "--material", "Au,Ag", "--no-plot"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream reflectance(dir / "metals_reflectance.csv");
    std::string header, first;
    std::getline(reflectance, header);
    std::getline(reflectance, first);
    EXPECT_EQ(header, "wavelength_nm,Au,Ag");
    EXPECT_EQ(first.rfind("380,", 0), 0u);
    std::ifstream swatches(dir / "metals_swatches.csv");
    std::string line;
    std::getline(swatches, line);
    std::getline(swatches, line);  // Au
    ASSERT_EQ(line.rfind("Au,", 0), 0u);
    // Gold under the lamp, white-balanced: red > green > blue (8-bit columns 10-12).
    std::vector<std::string> fields;
    std::stringstream s(line);
    for (std::string f; std::getline(s, f, ',');) fields.push_back(f);
    ASSERT_EQ(fields.size(), 18u);
    EXPECT_GT(std::stoi(fields[9]), std::stoi(fields[10]));
    EXPECT_GT(std::stoi(fields[10]), std::stoi(fields[11]));
    EXPECT_TRUE(std::filesystem::exists(dir / "metals_swatches.json"));
    std::filesystem::remove_all(dir);
    expect_bad_input({"metals", "--out", dir.string(), "--temperature", "-5", "--no-plot"}, "--temperature");
}
