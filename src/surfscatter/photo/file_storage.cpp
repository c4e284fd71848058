#include "surfscatter/photo/file_storage.hpp"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <stdexcept>
#include <thread>

#include <opencv2/core.hpp>

#include "surfscatter/core/error.hpp"

namespace surfscatter::photo {

namespace {

// How long OpenCV's parser may take on one file in the trial run; real camera files and dictionaries take
// milliseconds.
constexpr auto kParseTimeLimit = std::chrono::seconds(10);

// OpenCV's YAML parser loops forever on some malformed files (found by fuzz_camera_file: a line starting with '-'
// after what it takes for the end of the first document), and no option bounds it. So the file is first parsed in a
// child process that is killed after kParseTimeLimit; how that parse ends otherwise (an exception, a crash) is left to
// the real parse to report.
void require_parse_finishes(const std::string& path, const char* what) {
    const pid_t child = fork();
    if (child < 0) fail("{} '{}': cannot start the trial parse (fork failed)", what, path);
    if (child == 0) {
        try {
            cv::FileStorage fs(path, cv::FileStorage::READ);
            _exit(fs.isOpened() ? 0 : 1);
        } catch (...) {
            _exit(1);
        }
    }
    const auto start = std::chrono::steady_clock::now();
    auto pause = std::chrono::microseconds(100);
    int status = 0;
    while (waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() - start > kParseTimeLimit) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
            fail("{} '{}' is not valid YAML/XML/JSON: OpenCV's parser does not finish on it (stopped after {} s)", what,
                 path, std::chrono::duration_cast<std::chrono::seconds>(kParseTimeLimit).count());
        }
        std::this_thread::sleep_for(pause);
        pause = std::min(2 * pause, std::chrono::microseconds(20000));
    }
}

}  // namespace

void open_for_reading(cv::FileStorage& fs, const std::string& path, const char* what) {
    if (!std::filesystem::exists(path)) fail("{} '{}' does not exist", what, path);
    if (std::filesystem::is_directory(path)) fail("{} '{}' is a directory, not a .yml, .xml or .json file", what, path);
    if (!std::filesystem::is_regular_file(path)) fail("{} '{}' is not a regular file (a device or pipe)", what, path);
    require_parse_finishes(path, what);
    try {
        fs.open(path, cv::FileStorage::READ);
    } catch (const cv::Exception& e) {
        fail("{} '{}' is not valid YAML/XML/JSON: {}", what, path, printable(e.err, 200));
    } catch (const std::exception& e) {
        fail("{} '{}' is not valid YAML/XML/JSON (OpenCV's parser failed: {})", what, path, printable(e.what()));
    }
    if (!fs.isOpened()) fail("{} '{}' could not be read as YAML/XML/JSON", what, path);
}

}  // namespace surfscatter::photo
