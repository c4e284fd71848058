#pragma once
// Shared by the libFuzzer targets (fuzz/README.md). A target feeds the fuzzer's bytes to one reader: a
// surfscatter::Error is the expected answer to bad input; any other exception, a crash, a sanitizer report, a hang
// or a NaN in what the reader returns is a finding (FUZZ_CHECK aborts so that libFuzzer saves the input).
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "surfscatter/core/error.hpp"

namespace surfscatter::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// A scratch directory of this process (readers that take a path get the input as a file there).
inline const std::filesystem::path& scratch() {
    static const std::filesystem::path dir = [] {
        const auto d = std::filesystem::temp_directory_path() / ("surfscatter_fuzz_" + std::to_string(getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    return dir;
}

inline std::filesystem::path write_input(const std::string& name, std::string_view bytes) {
    const auto path = scratch() / name;
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    return path;
}

#define FUZZ_CHECK(condition)                                                                            \
    do {                                                                                                 \
        if (!(condition)) {                                                                              \
            std::fprintf(stderr, "fuzz check failed: %s (%s:%d)\n", #condition, __FILE__, __LINE__);     \
            std::abort();                                                                                \
        }                                                                                                \
    } while (0)

// Runs `read` on the input; Error is bad input handled well, anything else escapes to libFuzzer.
template <typename F>
void expect_clean(F&& read) {
    try {
        read();
    } catch (const Error& e) {
        // The message reaches a terminal: one line.
        if (std::string_view(e.what()).find('\n') != std::string_view::npos) {
            std::fprintf(stderr, "fuzz check failed: message with a line break: %s\n", e.what());
            std::abort();
        }
    }
}

}  // namespace surfscatter::fuzz
