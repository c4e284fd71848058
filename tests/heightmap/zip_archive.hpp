#pragma once
// Writes zip archives for tests of zip-based height map files (X3P): libzip, entries stored as given.
#include <gtest/gtest.h>
#include <zip.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace surfscatter::test {

// (entry name, bytes) pairs; an existing file at `path` is replaced.
inline void write_zip(const std::filesystem::path& path, const std::vector<std::pair<std::string, std::string>>& entries) {
    std::filesystem::remove(path);
    int code = 0;
    zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
    ASSERT_NE(archive, nullptr) << "libzip error " << code;
    // libzip reads the buffers at zip_close: `entries` outlives it.
    for (const auto& [name, bytes] : entries) {
        zip_source_t* source = zip_source_buffer(archive, bytes.data(), bytes.size(), 0);
        ASSERT_NE(source, nullptr);
        ASSERT_GE(zip_file_add(archive, name.c_str(), source, ZIP_FL_OVERWRITE), 0) << zip_strerror(archive);
    }
    ASSERT_EQ(zip_close(archive), 0);
}

}  // namespace surfscatter::test
