// End-to-end: `surfscatter surface synth` and `surfscatter surface fit` through the binary.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::run_cli;

namespace {

fs::path temp_dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_heightmap"); }

// "name = value" lines of stdout.
std::map<std::string, double> parse_values(const surfscatter::test::CliResult& result) {
    std::map<std::string, double> values;
    for (const std::string& line : result.out_lines()) {
        const auto eq = line.find(" = ");
        if (eq != std::string::npos) values[line.substr(0, eq)] = std::stod(line.substr(eq + 3));
    }
    return values;
}

}  // namespace

TEST(CliHeightmap, SynthThenFitRecoversParameters) {
    const std::string gsf = (temp_dir() / "kc.gsf").string();
    const auto synth = run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.05", "--corr-length", "2",
                                "--gamma", "3", "--size", "1024", "--spacing", "0.5", "--seed", "9", "-o", gsf});
    ASSERT_EQ(synth.exit_code, 0) << synth.err;
    ASSERT_TRUE(fs::exists(gsf));
    EXPECT_EQ(fs::file_size(gsf) % 4, 0u);

    const std::string png = (temp_dir() / "psd.png").string(), csv = (temp_dir() / "psd.csv").string();
    fs::remove(png);
    fs::remove(csv);
    const auto fit = run_cli({"surface", "fit", gsf, "--max-zeta-fraction", "1", "--plot", png, "--csv", csv});
    ASSERT_EQ(fit.exit_code, 0) << fit.err;
    const auto values = parse_values(fit);
    for (const char* name : {"sigma_h", "corr_length", "gamma", "rms_slope"})
        ASSERT_TRUE(values.count(name)) << "missing line '" << name << " = ...' in\n" << fit.out;
    EXPECT_NEAR(values.at("sigma_h") / 0.05, 1.0, 0.05);
    EXPECT_NEAR(values.at("corr_length") / 2.0, 1.0, 0.05);
    EXPECT_NEAR(values.at("gamma") / 3.0, 1.0, 0.05);
    EXPECT_GT(values.at("rms_slope"), 0.0);
    EXPECT_TRUE(fs::exists(png));
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "zeta,psd,count,kc_fit,in_band");
}

TEST(CliHeightmap, SameSeedSameFile) {
    const std::string a = (temp_dir() / "a.gsf").string(), b = (temp_dir() / "b.gsf").string();
    for (const std::string& out : {a, b})
        ASSERT_EQ(run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.1", "--corr-length", "3", "--gamma",
                           "2.5", "--size", "64", "--spacing", "0.5", "--seed", "3", "-o", out})
                      .exit_code,
                  0);
    EXPECT_EQ(surfscatter::test::read_whole_file(a), surfscatter::test::read_whole_file(b));
}

TEST(CliHeightmap, CsvGridNeedsSpacing) {
    const fs::path csv = temp_dir() / "grid.csv";
    {
        std::ofstream out(csv);
        for (int iy = 0; iy < 64; ++iy)
            for (int ix = 0; ix < 64; ++ix)
                out << 0.01 * std::sin(0.7 * ix + 0.1 * iy * iy) + 0.02 * std::cos(0.31 * ix * iy)
                    << (ix == 63 ? "\n" : ",");
    }
    const auto missing = run_cli({"surface", "fit", csv.string()});
    EXPECT_EQ(missing.exit_code, 2);
    EXPECT_NE(missing.err.find("--spacing"), std::string::npos) << missing.err;
    const auto bad = run_cli({"surface", "fit", csv.string(), "--spacing", "0"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find("--spacing"), std::string::npos) << bad.err;
}

TEST(CliHeightmap, BadInputExitsWithStatus2AndOneLine) {
    const fs::path dir = temp_dir();
    const std::string out = (dir / "x.gsf").string();
    struct Case {
        std::initializer_list<std::string> args;
        const char* expected;
    };
    const std::string truncated = (dir / "truncated.gsf").string();
    {
        std::ofstream f(truncated, std::ios::binary);
        f << "Gwyddion Simple Field 1.0\nXRes = 16\nYRes = 16\nXYUnits = m\nZUnits = m\n";
        f.write("\0\0\0", 3);
        f << "only a few bytes";
    }
    const std::string nan_csv = (dir / "nan.csv").string();
    {
        std::ofstream f(nan_csv);
        for (int i = 0; i < 8; ++i) f << (i == 4 ? "1,2,NaN,4,5,6,7,8\n" : "1,2,3,4,5,6,7,8\n");
    }
    for (const auto& [args, expected] : std::initializer_list<Case>{
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "1", "--size", "64",
               "--spacing", "0.5", "-o", out},
              "--gamma"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "0.5", "--size", "64",
               "--spacing", "0.5", "-o", out},
              "--gamma"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size", "4",
               "--spacing", "0.5", "-o", out},
              "--size"},
             {{"surface", "synth", "--sigma", "0.1", "--corr-length", "2", "--gamma", "3", "--size", "64",
               "--spacing", "-1", "-o", out},
              "--spacing"},
             {{"surface", "synth", "--sigma", "-0.1", "--corr-length", "2", "--gamma", "3", "--size", "64",
               "--spacing", "1", "-o", out},
              "--sigma"},
             {{"surface", "synth", "--model", "fractal", "--sigma", "0.1", "--corr-length", "2", "--size", "64",
               "--spacing", "1", "-o", out},
              "--model"},
             {{"surface", "fit", truncated}, "truncated"},
             {{"surface", "fit", nan_csv, "--spacing", "1"}, "nan.csv:5: column 3"},
             {{"surface", "fit", (dir / "missing.gsf").string()}, "cannot open"},
             {{"surface", "fit"}, "map"},
         }) {
        const auto result = run_cli(args);
        EXPECT_EQ(result.exit_code, 2) << result.err;
        EXPECT_NE(result.err.find(expected), std::string::npos) << result.err;
        EXPECT_EQ(result.out, "");
    }
}
