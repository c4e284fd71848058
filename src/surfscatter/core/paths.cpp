#include "surfscatter/core/paths.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "surfscatter/core/error.hpp"

namespace surfscatter {

namespace {
std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? std::string(v) : std::string();
}

std::string shell_quote(const std::string& s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'') out += "'\\''";
        else out += c;
    }
    return out + "'";
}
}  // namespace

std::filesystem::path cache_directory() {
    std::filesystem::path dir;
    if (auto d = env("SURFSCATTER_CACHE_DIR"); !d.empty()) dir = d;
    else if (auto x = env("XDG_CACHE_HOME"); !x.empty()) dir = std::filesystem::path(x) / "surfscatter";
    else if (auto h = env("HOME"); !h.empty()) dir = std::filesystem::path(h) / ".cache" / "surfscatter";
    else dir = std::filesystem::temp_directory_path() / "surfscatter-cache";
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) fail("cannot create cache directory {}: {}", dir.string(), ec.message());
    return dir;
}

std::string host_name() {
    char name[256] = {};
    if (gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "unknown-host";
    return name;
}

std::filesystem::path plot_script_directory() {
    if (auto d = env("SURFSCATTER_PLOT_SCRIPTS"); !d.empty()) return d;
    return std::filesystem::path(SURFSCATTER_SOURCE_DIR) / "scripts" / "plot";
}

void run_plot_script(const std::string& script, const std::vector<std::string>& args) {
    const auto path = plot_script_directory() / script;
    if (!std::filesystem::exists(path)) fail("plot script not found: {}", path.string());
    // The script's stderr goes to a file: on failure its last line (scripts/plot/plotting.py makes it the one line
    // naming the output and the reason) becomes the Error's message, instead of reaching the terminal raw.
    std::string log = (std::filesystem::temp_directory_path() / "surfscatter-plot-XXXXXX").string();
    const int fd = mkstemp(log.data());
    if (fd < 0) fail("cannot create a temporary file for plot script {}: {}", script, std::strerror(errno));
    close(fd);
    // Appended piece by piece: `" " + std::string` trips g++ 12's false -Wrestrict warning.
    std::string cmd = "/usr/bin/python3 ";
    cmd += shell_quote(path.string());
    for (const auto& a : args) {
        cmd += ' ';
        cmd += shell_quote(a);
    }
    cmd += " 2>";
    cmd += shell_quote(log);
    const int status = std::system(cmd.c_str());
    std::string last;
    {
        std::ifstream in(log);
        for (std::string line; std::getline(in, line);)
            if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
    }
    std::error_code ec;
    std::filesystem::remove(log, ec);
    if (status == 0) return;
    if (status == -1) fail("cannot run plot script {}: {}", script, std::strerror(errno));
    if (WIFSIGNALED(status)) fail("plot script {} was stopped by signal {}", script, WTERMSIG(status));
    if (!last.empty()) fail("{}", printable(last, 2 * kShownPathChars));
    fail("plot script {} failed with exit status {}", script, WEXITSTATUS(status));
}

}  // namespace surfscatter
