// Defensive input reading and resource limits (core/input_file.hpp, core/resources.hpp, printable()).
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <future>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "error_of.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/input_file.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/core/table_cache.hpp"

namespace surfscatter {

using test::error_of;

TEST(Printable, EscapesBinaryAndCutsLongText) {
    EXPECT_EQ(printable("plain text"), "plain text");
    EXPECT_EQ(printable(std::string("a\0b\n\x1b[31m\xff", 10)), "a\\x00b\\x0a\\x1b[31m\\xff");
    EXPECT_EQ(printable(std::string(100, 'x'), 5), "xxxxx...");
    EXPECT_EQ(printable("", 5), "");
}

TEST(InputFile, ReadsFilesAndRefusesDirectoriesDevicesAndOversizedInput) {
    const auto dir = std::filesystem::temp_directory_path() / "surfscatter_test_input";
    std::filesystem::create_directories(dir / "a_directory.xml");
    std::ofstream(dir / "small.txt") << "hello";
    EXPECT_EQ(read_input_file(dir / "small.txt", "text file"), "hello");
    EXPECT_EQ(error_of([&] { read_input_file(dir / "missing.txt", "text file"); }),
              "text file not found: " + (dir / "missing.txt").string());
    EXPECT_EQ(error_of([&] { read_input_file(dir / "a_directory.xml", "scene file"); }),
              "scene file " + (dir / "a_directory.xml").string() + " is a directory, not a file");
    EXPECT_NE(error_of([&] { read_input_file("/dev/zero", "scene file"); }).find("is not a regular file"),
              std::string::npos);
    EXPECT_NE(error_of([&] { read_input_file(dir / "small.txt", "text file", 4); }).find("is larger than the 4 bytes"),
              std::string::npos);
    const std::string long_name = (dir / (std::string(300, 'a') + ".yml")).string();
    EXPECT_NE(error_of([&] { read_input_file(long_name, "refractive index file"); }).find("File name too long"),
              std::string::npos);
}

TEST(Resources, LimitsThreadsAndMemory) {
    EXPECT_NO_THROW(require_thread_count(0, "--threads"));
    EXPECT_NO_THROW(require_thread_count(kMaxThreads, "--threads"));
    EXPECT_EQ(error_of([] { require_thread_count(100000, "--threads"); }),
              "--threads must be between 1 and 256 (or 0 for all cores), got 100000");
    EXPECT_EQ(error_of([] { require_thread_count(-1, "--threads"); }),
              "--threads must be between 1 and 256 (or 0 for all cores), got -1");
    EXPECT_GT(available_memory_bytes(), 1u << 20);
    EXPECT_NO_THROW(require_memory(1024.0, "a small buffer"));
    EXPECT_NE(error_of([] { require_memory(1e30, "a huge film"); }).find("a huge film needs 8.674e+11 EiB of memory, more than the"),
              std::string::npos);
    EXPECT_EQ(format_bytes(512), "512 bytes");
    EXPECT_EQ(format_bytes(1536.0 * 1024 * 1024), "1.5 GiB");
}

// Issue 26: a FIFO where the table cache expects a table blocked the open forever; it is now passed over (the table
// is rebuilt), and read_input_file refuses a FIFO by name. Each call runs under a 10 s watchdog that opens the FIFO for
// writing if the call still waits, so that a regression fails instead of hanging.
TEST(SpecialFiles, FifoIsRefusedAndTheCachePassesOverIt) {
    const auto fifo = std::filesystem::temp_directory_path() / ("surfscatter_fifo_" + std::to_string(getpid()));
    std::filesystem::remove(fifo);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0644), 0);
    auto finishes = [&](const std::function<void()>& call) {
        auto done = std::async(std::launch::async, call);
        if (done.wait_for(std::chrono::seconds(10)) == std::future_status::ready) return true;
        const int unblock = open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
        done.wait();
        if (unblock >= 0) close(unblock);
        return false;
    };
    bool cached = true;
    EXPECT_TRUE(finishes([&] { cached = load_cached_table(fifo, 1, "key").has_value(); })) << "the cache blocked";
    EXPECT_FALSE(cached);
    std::string message;
    EXPECT_TRUE(finishes([&] { message = error_of([&] { read_input_file(fifo, "scene file"); }); }));
    EXPECT_EQ(message, "scene file " + fifo.string() + " is a FIFO (named pipe), not a file");
    std::filesystem::remove(fifo);
}

}  // namespace surfscatter
