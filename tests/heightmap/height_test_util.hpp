#pragma once
// Helpers shared by the height map tests: error messages and scratch files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap::test {

// The square map turned by +90 deg (from +x towards +y): h'(X, Y) = h(Y, N - 1 - X).
inline heightmap::HeightMap turned(const heightmap::HeightMap& map) {
    const std::size_t n = map.nx();
    std::vector<double> heights(n * n);
    for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) heights[y * n + x] = map(y, n - 1 - x);
    return heightmap::HeightMap(n, n, map.spacing_x(), map.spacing_y(), std::move(heights), "turned");
}

// Runs f and returns the Error message (fails the test if nothing is thrown).
template <typename F>
std::string error_of(F&& f) {
    try {
        f();
    } catch (const surfscatter::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no surfscatter::Error thrown";
    return {};
}

// `name` in a scratch directory of the system temp directory (created if missing).
inline std::filesystem::path temp_path(const std::string& directory, const std::string& name) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / directory;
    std::filesystem::create_directories(dir);
    return dir / name;
}

inline void write_bytes(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace surfscatter::heightmap::test
