// Issue 36, class 1: the one rule for outputs (core/output_files.hpp). An output never replaces an input or another
// output, however the same file is named (a second spelling, "..", a symbolic link, a hard link); a set of outputs
// lands together or not at all (a full disk leaves every old file and no temporary file); a name of 255 bytes works.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "error_of.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"

namespace surfscatter {

namespace fs = std::filesystem;
using test::error_of;

namespace {

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "surfscatter_test_output_files" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// What a folder holds besides `expected` (a temporary file left behind, a file written when none should be).
std::vector<std::string> others(const fs::path& folder, const std::vector<std::string>& expected) {
    std::vector<std::string> found;
    for (const auto& entry : fs::directory_iterator(folder)) {
        const std::string name = entry.path().filename().string();
        if (std::find(expected.begin(), expected.end(), name) == expected.end()) found.push_back(name);
    }
    return found;
}

// Writes beyond `bytes` fail with EFBIG (a full disk) while one lives: RLIMIT_FSIZE with SIGXFSZ ignored.
class FullDisk {
public:
    explicit FullDisk(rlim_t bytes) {
        getrlimit(RLIMIT_FSIZE, &old_);
        old_handler_ = signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{bytes, old_.rlim_max};
        setrlimit(RLIMIT_FSIZE, &limit);
    }
    ~FullDisk() {
        setrlimit(RLIMIT_FSIZE, &old_);
        signal(SIGXFSZ, old_handler_);
    }

private:
    rlimit old_{};
    sighandler_t old_handler_;
};

}  // namespace

TEST(OutputFiles, AnOutputNeverReplacesAnInputHoweverItIsNamed) {
    const fs::path dir = scratch("inputs");
    std::ofstream(dir / "scan.csv") << "measured";
    fs::create_directories(dir / "sub");
    fs::create_symlink(dir / "scan.csv", dir / "link.csv");
    fs::create_hard_link(dir / "scan.csv", dir / "hard.csv");
    for (const fs::path& output : {dir / "scan.csv", dir / "sub" / ".." / "scan.csv", dir / "link.csv", dir / "hard.csv"}) {
        OutputFiles files;
        files.input(dir / "scan.csv", "--surface");
        EXPECT_EQ(error_of([&] { files.output(output, "-o"); }),
                  "-o " + output.string() + " would replace the input --surface " + (dir / "scan.csv").string() +
                      ": name another output");
    }
    // Relative and absolute spellings are one file.
    const fs::path cwd = fs::current_path();
    fs::current_path(dir);
    OutputFiles files;
    files.input("scan.csv", "--profile");
    EXPECT_NE(error_of([&] { files.output(dir / "scan.csv", "-o"); }).find("would replace the input --profile scan.csv"),
              std::string::npos);
    fs::current_path(cwd);
    EXPECT_EQ(contents(dir / "scan.csv"), "measured");
}

TEST(OutputFiles, TwoOutputsNeverShareAFileAndInputsThatDoNotExistAreSkipped) {
    const fs::path dir = scratch("outputs");
    OutputFiles files;
    files.input(dir / "missing.csv", "--material");  // names nothing: reading it fails on its own
    files.input("Au", "--material");                 // a built-in name, not a file
    files.output(dir / "missing.csv", "-o");
    EXPECT_EQ(error_of([&] { files.output(dir / "missing.csv", "the PNG beside -o"); }),
              "the PNG beside -o " + (dir / "missing.csv").string() + " and -o " + (dir / "missing.csv").string() +
                  " are the same file: name another output");
}

// Outputs a later step writes into folders it makes (a study's jobs): the same rule against inputs and each other,
// their folders not yet there.
TEST(OutputFiles, PlannedOutputsFollowTheSameRuleBeforeTheirFoldersExist) {
    const fs::path dir = scratch("planned");
    std::ofstream(dir / "map.gsf") << "x";
    OutputFiles files;
    files.input(dir / "map.gsf", "'map.gsf' of job a");
    EXPECT_NO_THROW(files.plan(dir / "renders" / "a.png", "job a's output"));
    EXPECT_EQ(error_of([&] { files.plan(dir / "renders" / ".." / "renders" / "a.png", "job b's output"); }),
              "job b's output " + (dir / "renders" / ".." / "renders" / "a.png").string() + " and job a's output " +
                  (dir / "renders" / "a.png").string() + " are the same file: name another output");
    EXPECT_NE(error_of([&] { files.plan(dir / "map.gsf", "job c's output"); }).find("would replace the input 'map.gsf' of job a"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "renders"));
}

TEST(OutputFiles, RefusesFoldersDevicesAndMissingFoldersBeforeAnyWork) {
    const fs::path dir = scratch("where");
    OutputFiles files;
    EXPECT_EQ(error_of([&] { files.output(dir, "-o"); }), "-o " + dir.string() + " is a folder: name a file in it");
    EXPECT_EQ(error_of([&] { files.output("/dev/full", "-o"); }),
              "-o /dev/full is not a regular file (a device, FIFO or socket): name a file");
    EXPECT_EQ(error_of([&] { files.output(dir / "no" / "x.csv", "-o"); }),
              "cannot write -o " + (dir / "no" / "x.csv").string() + ": folder " + (dir / "no").string() +
                  " does not exist");
    std::ofstream(dir / "file") << "x";
    EXPECT_EQ(error_of([&] { files.output(dir / "file" / "x.csv", "-o"); }),
              "cannot write -o " + (dir / "file" / "x.csv").string() + ": folder " + (dir / "file").string() +
                  " is not a folder");
    EXPECT_EQ(error_of([&] { files.output("", "--csv"); }), "--csv is empty: name a file");
    const fs::path too_long = dir / (std::string(252, 'n') + ".json");
    EXPECT_EQ(error_of([&] { files.output(too_long, "-o's JSON"); }),
              "cannot write -o's JSON " + printable(too_long.string(), kShownPathChars) +
                  ": its name is longer than the 255 bytes the file system allows");
}

TEST(OutputFiles, ASetLandsTogetherOrNotAtAll) {
    const fs::path dir = scratch("together");
    std::ofstream(dir / "a.csv") << "old a";
    std::ofstream(dir / "b.json") << "old b";
    {
        OutputFiles files;
        files.output(dir / "a.csv", "-o");
        files.output(dir / "b.json", "the JSON beside -o");
        files.write(dir / "a.csv", "new a");
        EXPECT_EQ(contents(dir / "a.csv"), "old a");  // nothing lands before commit()
        const std::string big(20000, 'x');
        const FullDisk full(8192);
        EXPECT_EQ(error_of([&] { files.write(dir / "b.json", big); }),
                  "cannot write " + (dir / "b.json").string() + ": File too large");
    }  // not committed: the first output's temporary file goes too
    EXPECT_EQ(contents(dir / "a.csv"), "old a");
    EXPECT_EQ(contents(dir / "b.json"), "old b");
    EXPECT_EQ(others(dir, {"a.csv", "b.json"}), std::vector<std::string>{});

    OutputFiles files;
    files.output(dir / "a.csv", "-o");
    files.output(dir / "b.json", "the JSON beside -o");
    files.write(dir / "a.csv", "new a");
    files.write_with(dir / "b.json", [&](const fs::path& tmp) {
        EXPECT_EQ(contents(files.staged(dir / "a.csv")), "new a");  // a plot script reads what was written before it
        std::ofstream(tmp) << "new b";
    });
    files.commit();
    EXPECT_EQ(contents(dir / "a.csv"), "new a");
    EXPECT_EQ(contents(dir / "b.json"), "new b");
    EXPECT_EQ(others(dir, {"a.csv", "b.json"}), std::vector<std::string>{});
}

// A rename failing midway (here a folder put where the last output goes, after the outputs were declared) leaves
// the set as it was: the outputs renamed before it get their old files back, or go where there were none.
TEST(OutputFiles, ARenameFailingMidwayPutsTheSetBack) {
    const fs::path dir = scratch("rename");
    const std::vector<std::string> names = {"a.csv", "b.json", "c.png"};
    // Each declared and written with "new " and its first letter.
    const auto write_new = [&](OutputFiles& files) {
        for (const std::string& name : names) {
            files.output(dir / name, name);
            files.write(dir / name, "new " + name.substr(0, 1));
        }
    };
    std::ofstream(dir / "a.csv") << "old a";
    std::ofstream(dir / "c.png") << "old c";
    OutputFiles files;
    write_new(files);
    fs::remove(dir / "c.png");
    fs::create_directories(dir / "c.png" / "inside");
    EXPECT_EQ(error_of([&] { files.commit(); }),
              "cannot move " + (dir / "c.png").string() + " into place: Is a directory");
    EXPECT_EQ(contents(dir / "a.csv"), "old a");
    EXPECT_FALSE(fs::exists(dir / "b.json"));
    EXPECT_TRUE(fs::is_directory(dir / "c.png" / "inside"));
    EXPECT_EQ(others(dir, {"a.csv", "c.png"}), std::vector<std::string>{});  // no temporary or kept file
    // The same set commits once the folder is gone; the old files kept meanwhile are removed.
    fs::remove_all(dir / "c.png");
    std::ofstream(dir / "c.png") << "old c";
    OutputFiles again;
    write_new(again);
    again.commit();
    for (const std::string& name : names) EXPECT_EQ(contents(dir / name), "new " + name.substr(0, 1));
    EXPECT_EQ(others(dir, names), std::vector<std::string>{});
}

TEST(OutputFiles, AWritersErrorNamesTheOutputNotTheTemporaryFile) {
    const fs::path dir = scratch("writer");
    OutputFiles files;
    files.output(dir / "plot.png", "--plot");
    EXPECT_EQ(error_of([&] {
                  files.write_with(dir / "plot.png", [](const fs::path& tmp) {
                      std::ofstream(tmp) << "part of a plot";
                      fail("plot.py: cannot write {}: No space left on device", tmp.string());
                  });
              }),
              "plot.py: cannot write " + (dir / "plot.png").string() + ": No space left on device");
    EXPECT_EQ(error_of([&] { files.write_with(dir / "plot.png", [](const fs::path&) {}); }),
              "cannot write " + (dir / "plot.png").string() + ": nothing was written");
    files.commit();
    EXPECT_EQ(others(dir, {}), std::vector<std::string>{});
}

TEST(OutputFiles, ANameOf255BytesIsWrittenAndSymbolicLinksStay) {
    const fs::path dir = scratch("long");
    const fs::path output = dir / (std::string(251, 'n') + ".csv");
    ASSERT_EQ(output.filename().string().size(), 255u);
    write_file_atomically(output, "long");
    EXPECT_EQ(contents(output), "long");
    EXPECT_LE(temporary_beside(output).filename().string().size(), 40u);
    EXPECT_EQ(temporary_beside(output).extension(), ".csv");

    // Writing through a symbolic link replaces its target, not the link.
    std::ofstream(dir / "target.csv") << "old";
    fs::create_symlink(dir / "target.csv", dir / "link.csv");
    write_file_atomically(dir / "link.csv", "new");
    EXPECT_TRUE(fs::is_symlink(dir / "link.csv"));
    EXPECT_EQ(contents(dir / "target.csv"), "new");
}

}  // namespace surfscatter
