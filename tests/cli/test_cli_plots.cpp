// Issue 36, class 4: a command whose plot cannot be written (wrong extension, read-only folder, full disk) exits 2
// with one line naming the plot and the reason - the plot script's own line (scripts/plot/plotting.py), passed on by
// run_plot_script (core/paths.cpp) - never a Python traceback or "is python3-matplotlib installed?", and leaves no
// partial or temporary file. Ctrl-C and a missing matplotlib are covered at the scripts (tests/cli/test_plot_scripts.py).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

namespace fs = std::filesystem;
using surfscatter::test::CliResult;
using surfscatter::test::run_cli;

namespace {

fs::path dir() { return surfscatter::test::scratch_directory("surfscatter_test_cli_plots"); }

// A cheap command with a plot: GGX's in-plane slice, its CSV in the scratch folder, its PNG at `plot`.
CliResult slice_with_plot(const fs::path& csv, const fs::path& plot, const std::string& shell_prefix = "") {
    return run_cli({"brdf", "slice", "--model", "ggx_stats", "--alpha", "0.2", "--material", "Au", "--wavelength", "550",
                    "--theta-i", "30", "--csv", csv.string(), "--plot", plot.string()},
                   120, shell_prefix);
}

// Exit 2 and stderr one line holding `expected`, with nothing of a traceback or of the old hint.
void expect_one_line(const CliResult& r, const std::string& expected) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "more than one line:\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("Traceback"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("is python3-matplotlib installed"), std::string::npos) << r.err;
}

// Temporary files in `folder` (core/output_files.hpp's and plotting.py's names start with ".ss-").
std::vector<std::string> temporaries(const fs::path& folder) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(folder))
        if (entry.path().filename().string().rfind(".ss-", 0) == 0) found.push_back(entry.path().filename());
    return found;
}

// `surface info --plot` of the example map: a ring table of a few KiB beside a plot of tens of KiB.
CliResult info_with_plot(const fs::path& plot, const std::string& shell_prefix = "") {
    return run_cli({"surface", "info", std::string(SURFSCATTER_SOURCE_DIR) + "/examples/data/kc_surface.gsf", "--plot",
                    plot.string()},
                   120, shell_prefix);
}

TEST(CliPlots, APlotIsWritten) {
    CliResult r = slice_with_plot(dir() / "ok.csv", dir() / "ok.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(temporaries(dir()).empty());
    r = info_with_plot(dir() / "info.png");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_GT(fs::file_size(dir() / "info.png"), 8192u);  // the full-disk case below needs a plot beyond 8 KiB
    EXPECT_LT(fs::file_size(dir() / "info.csv"), 8192u);  // and its table within
}

TEST(CliPlots, WrongExtensionNamesThePlotAndTheReason) {
    const fs::path plot = dir() / "slice.xyz";
    expect_one_line(slice_with_plot(dir() / "ext.csv", plot),
                    "brdf_slice.py: cannot write " + plot.string() + ": the extension .xyz is not an image format");
    EXPECT_FALSE(fs::exists(plot));
    EXPECT_TRUE(temporaries(dir()).empty());
}

TEST(CliPlots, ReadOnlyFolder) {
    // Root ignores permission bits: for root the folder is made immutable (chattr +i), otherwise mode 0555.
    const fs::path folder = dir() / "read-only";
    const bool root = geteuid() == 0;
    if (root) std::system(("chattr -i '" + folder.string() + "' 2>/dev/null").c_str());
    fs::remove_all(folder);
    fs::create_directories(folder);
    if (root) ASSERT_EQ(std::system(("chattr +i '" + folder.string() + "'").c_str()), 0);
    else fs::permissions(folder, fs::perms::owner_read | fs::perms::owner_exec);
    const fs::path plot = folder / "slice.png";
    const CliResult r = slice_with_plot(dir() / "ro.csv", plot);
    if (root) EXPECT_EQ(std::system(("chattr -i '" + folder.string() + "'").c_str()), 0);
    else fs::permissions(folder, fs::perms::owner_all);
    // Refused before the work: the folder cannot take the output.
    expect_one_line(r, "cannot write --plot " + plot.string() + ": folder " + folder.string() + ": " +
                           (root ? "Operation not permitted" : "Permission denied"));
    EXPECT_TRUE(fs::is_empty(folder));
}

TEST(CliPlots, FullDiskKeepsTheOldPlotAndLeavesNoTemporaryFile) {
    // `ulimit -f 16` with SIGXFSZ ignored: writes beyond 8 KiB fail with EFBIG, as on a full disk. The CSV fits.
    const fs::path folder = dir() / "full";
    fs::remove_all(folder);
    fs::create_directories(folder);
    const fs::path plot = folder / "slice.png";
    std::ofstream(plot) << "the previous plot";
    std::ofstream(folder / "slice.csv") << "the previous table";  // the plot's CSV lands with it or not at all
    expect_one_line(info_with_plot(plot, "trap '' XFSZ; ulimit -f 16; "),
                    "psd_fit.py: cannot write " + plot.string() + ": File too large");
    EXPECT_EQ(surfscatter::test::read_whole_file(plot.string()), "the previous plot");
    EXPECT_EQ(surfscatter::test::read_whole_file((folder / "slice.csv").string()), "the previous table");
    EXPECT_TRUE(temporaries(folder).empty());
}

}  // namespace
