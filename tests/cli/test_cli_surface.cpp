// End-to-end: `surfscatter psd`, `acv` and `selfconv` through the binary (exact output forms of issue 3 item 7,
// numbers against the closed forms, bad input -> one error line and exit status 2).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::CliResult;
using surfscatter::test::run_cli;

namespace {

std::vector<std::vector<double>> csv_rows(const std::vector<std::string>& lines, std::size_t first) {
    std::vector<std::vector<double>> rows;
    for (std::size_t i = first; i < lines.size(); ++i) {
        std::vector<double> row;
        std::stringstream ss(lines[i]);
        for (std::string cell; std::getline(ss, cell, ',');) row.push_back(std::stod(cell));
        rows.push_back(row);
    }
    return rows;
}

void expect_usage_error(const CliResult& r) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    EXPECT_FALSE(r.err.empty());
}

TEST(CliSurface, PsdKcAndGaussian) {
    const CliResult r = run_cli({"psd", "--model", "kc", "--sigma", "0.5", "--corr-length", "2", "--gamma", "3",
                                 "--zeta", "0,0.5,10"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "zeta,psd");
    const auto rows = csv_rows(lines, 1);
    for (const auto& row : rows) {
        const double expected = 0.25 * 2.0 * 4.0 / (2 * M_PI) * std::pow(1 + 4.0 * row[0] * row[0], -2.0);
        EXPECT_NEAR(row[1], expected, 1e-9 * expected);
    }
    const CliResult g = run_cli({"psd", "--model", "gaussian", "--sigma", "2.27", "--corr-length", "20.9", "--zeta", "0.05"});
    ASSERT_EQ(g.exit_code, 0) << g.err;
    const double expected = 2.27 * 2.27 * 20.9 * 20.9 / (4 * M_PI) * std::exp(-0.25 * 20.9 * 20.9 * 0.0025);
    EXPECT_NEAR(csv_rows(g.out_lines(), 1)[0][1], expected, 1e-9 * expected);
}

TEST(CliSurface, AcvKc) {
    const CliResult r = run_cli({"acv", "--model", "kc", "--sigma", "2", "--corr-length", "1.5", "--gamma", "2",
                                 "--r", "0,1.5,3"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_EQ(lines[0], "r,acv");
    for (const auto& row : csv_rows(lines, 1)) EXPECT_NEAR(row[1], 4.0 * std::exp(-row[0] / 1.5), 1e-9);
}

TEST(CliSurface, SelfconvGamma2IsExact) {
    const fs::path dir = fs::temp_directory_path() / "surfscatter_test_cli_surface";
    fs::create_directories(dir);
    const std::string table = (dir / "table.csv").string();
    const CliResult r = run_cli({"selfconv", "--gamma", "2", "--corr-length", "1", "--orders", "8", "--out", table});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto lines = r.out_lines();
    ASSERT_EQ(lines.size(), 10u);
    ASSERT_EQ(lines[0].rfind("x = ", 0), 0u) << lines[0];
    EXPECT_NEAR(std::stod(lines[0].substr(4)), 1.0, 1e-6);
    EXPECT_EQ(lines[1], "m,L_m,misfit");
    const auto rows = csv_rows(lines, 2);
    for (const auto& row : rows) EXPECT_NEAR(row[1], 1.0 / row[0], 1e-6);
    EXPECT_EQ(surfscatter::test::read_whole_file(table).substr(0, 12), "m,L_m,misfit");
}

TEST(CliSurface, SelfconvPlotWritesPng) {
    const fs::path dir = fs::temp_directory_path() / "surfscatter_test_cli_surface";
    fs::create_directories(dir);
    const fs::path png = dir / "fig2.png";
    fs::remove(png);
    const CliResult r = run_cli({"selfconv", "--gamma", "3", "--corr-length", "1", "--orders", "13", "--plot", png.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NEAR(std::stod(r.out_lines()[0].substr(4)), 0.70, 0.02);  // THEORY.md 2.4: x ~ 0.69 for gamma = 3
    EXPECT_GT(fs::file_size(png), 10000u);
}

TEST(CliSurface, BadInputExitsWith2) {
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "1", "--zeta", "1"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "-1", "--corr-length", "1", "--gamma", "3", "--zeta", "1"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "0", "--gamma", "3", "--zeta", "1"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "nan", "--corr-length", "1", "--gamma", "3", "--zeta", "1"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--zeta", "1,,2"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--zeta", "1,x"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "3", "--zeta", "-1"}));
    expect_usage_error(run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--zeta", "1"}));
    expect_usage_error(run_cli({"psd", "--model", "fractal", "--sigma", "1", "--corr-length", "1", "--zeta", "1"}));
    expect_usage_error(run_cli({"acv", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "0.5", "--r", "1"}));
    expect_usage_error(run_cli({"acv", "--model", "gaussian", "--sigma", "1", "--corr-length", "1", "--r", "inf"}));
    expect_usage_error(run_cli({"selfconv", "--gamma", "1", "--corr-length", "1", "--orders", "5"}));
    expect_usage_error(run_cli({"selfconv", "--gamma", "3", "--corr-length", "-2", "--orders", "5"}));
    expect_usage_error(run_cli({"selfconv", "--gamma", "3", "--corr-length", "1", "--orders", "0"}));
    expect_usage_error(run_cli({"selfconv", "--gamma", "nan", "--corr-length", "1", "--orders", "3"}));
    const CliResult r = run_cli({"psd", "--model", "kc", "--sigma", "1", "--corr-length", "1", "--gamma", "1", "--zeta", "1"});
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
