// CLI habits of issue 27: every subcommand says what it wrote, and --help lists only the options a command accepts.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::run_cli;

TEST(CliHabits, SurfaceSynthSaysWhatItWrote) {
    const fs::path dir = surfscatter::test::scratch_directory("surfscatter_cli_habits_synth");
    const std::string map = (dir / "kc.gsf").string();
    const auto r = run_cli({"surface", "synth", "--model", "kc", "--sigma", "0.05", "--corr-length", "1", "--gamma",
                            "3", "--size", "64", "--spacing", "0.1", "--seed", "2", "-o", map});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(fs::exists(map));
    EXPECT_NE(r.err.find("surfscatter: surface synth: wrote " + map + " (64 x 64 points of 0.1 um, kc sigma_h=0.05"),
              std::string::npos) << r.err;
    fs::remove_all(dir);
}

TEST(CliHabits, SelfconvSaysWhatItWrote) {
    const fs::path dir = surfscatter::test::scratch_directory("surfscatter_cli_habits_selfconv");
    const std::string csv = (dir / "table.csv").string();
    const auto r = run_cli({"selfconv", "--gamma", "3", "--corr-length", "1", "--orders", "3", "--out", csv});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("surfscatter: selfconv: wrote " + csv), std::string::npos) << r.err;
    fs::remove_all(dir);
}

// calibrate takes ChArUco and chess boards: the grid board's options are not offered (pose has them).
TEST(CliHabits, CalibrateHelpListsOnlyItsOptions) {
    const auto calibrate = run_cli({"calibrate", "--help"});
    ASSERT_EQ(calibrate.exit_code, 0) << calibrate.err;
    EXPECT_NE(calibrate.out.find("--squares"), std::string::npos) << calibrate.out;
    EXPECT_EQ(calibrate.out.find("--markers "), std::string::npos) << calibrate.out;
    EXPECT_EQ(calibrate.out.find("--marker-separation"), std::string::npos) << calibrate.out;
    const auto refused = run_cli({"calibrate", "a.png", "--markers", "5x7", "-o", "c.yml"});
    EXPECT_EQ(refused.exit_code, 2);
    const auto pose = run_cli({"pose", "--help"});
    EXPECT_NE(pose.out.find("--marker-separation"), std::string::npos) << pose.out;
}
