#pragma once
// Helpers shared by the height map tests: error messages and scratch files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "surfscatter/core/error.hpp"

namespace surfscatter::surface::test {

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

}  // namespace surfscatter::surface::test
