#pragma once
// Runs the surfscatter CLI (SURFSCATTER_CLI) in a shell and captures stdout, stderr and the exit status, for the
// end-to-end tests in tests/cli/. Arguments are single-quoted so paths with spaces work.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace surfscatter::test {

// The scratch directories this process made, removed when it exits.
struct ScratchDirectories {
    std::vector<std::filesystem::path> made;
    ~ScratchDirectories() {
        std::error_code ignored;  // a folder a test still holds open stays behind in the temp directory
        for (const auto& dir : made) std::filesystem::remove_all(dir, ignored);
    }
};
inline ScratchDirectories scratch_directories;

// A per-suite scratch directory under the system temp directory (created if missing), one per process: ctest runs
// every case in its own process, two at a time, and a suite that empties its folder in SetUpTestSuite emptied the
// other's under it (gtest then reported the case skipped, which ctest counts as no failure).
inline std::filesystem::path scratch_directory(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
    if (std::filesystem::create_directories(dir)) scratch_directories.made.push_back(dir);
    return dir;
}

struct CliResult {
    int exit_code = -1;
    std::string out;  // stdout
    std::string err;  // stderr

    // Lines of stdout without the trailing newline.
    std::vector<std::string> out_lines() const {
        std::vector<std::string> lines;
        std::istringstream in(out);
        for (std::string line; std::getline(in, line);) lines.push_back(line);
        return lines;
    }
};

inline std::string shell_quote(const std::string& arg) {
    std::string quoted = "'";
    for (char c : arg) quoted += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

inline std::string read_whole_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// run_cli({"ior", "--material", "Au", "--wavelength", "550"}). With `timeout_seconds` > 0 the command is killed
// after that long (exit code 137), so that a hang fails the test instead of stalling the suite. `shell_prefix` runs
// before it in the same shell ("ulimit -f 8;"); `stdout_path` takes its stdout instead of the capture ("/dev/full").
inline CliResult run_cli(const std::vector<std::string>& args, int timeout_seconds = 0,
                         const std::string& shell_prefix = "", const std::string& stdout_path = "") {
    char out_path[] = "/tmp/surfscatter_cli_out_XXXXXX";
    char err_path[] = "/tmp/surfscatter_cli_err_XXXXXX";
    const int out_fd = mkstemp(out_path);
    const int err_fd = mkstemp(err_path);
    if (out_fd >= 0) close(out_fd);
    if (err_fd >= 0) close(err_fd);
    std::string command = shell_prefix;
    if (timeout_seconds > 0) command += "timeout -s KILL " + std::to_string(timeout_seconds) + " ";
    command += shell_quote(SURFSCATTER_CLI);
    // Appended piece by piece: `" " + std::string` trips g++ 12's false -Wrestrict warning.
    for (const auto& a : args) {
        command += ' ';
        command += shell_quote(a);
    }
    command += " >";
    command += shell_quote(stdout_path.empty() ? std::string(out_path) : stdout_path);
    command += " 2>";
    command += shell_quote(err_path);
    command += " </dev/null";
    CliResult result;
    const int status = std::system(command.c_str());
    if (status != -1 && WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
    result.out = read_whole_file(out_path);
    result.err = read_whole_file(err_path);
    std::remove(out_path);
    std::remove(err_path);
    return result;
}

inline CliResult run_cli(std::initializer_list<std::string> args) { return run_cli(std::vector<std::string>(args)); }

}  // namespace surfscatter::test
