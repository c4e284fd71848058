#pragma once
// The disk cache (SURFSCATTER_CACHE_DIR) pointed at an empty folder of the benchmark's own under the temporary
// directory, for benchmarks that time what a first run builds. renew() moves it to a new empty subfolder, for an
// iteration that must not find the tables of the one before; the folder goes with the value.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace surfscatter::bench {

class EmptyCache {
public:
    explicit EmptyCache(const std::string& name) : root_(std::filesystem::temp_directory_path() / name) {
        std::filesystem::remove_all(root_);
        point_at(root_);
    }
    ~EmptyCache() { std::filesystem::remove_all(root_); }
    EmptyCache(const EmptyCache&) = delete;
    EmptyCache& operator=(const EmptyCache&) = delete;

    void renew() { point_at(root_ / std::to_string(++run_)); }

private:
    static void point_at(const std::filesystem::path& dir) {
        std::filesystem::create_directories(dir);
        setenv("SURFSCATTER_CACHE_DIR", dir.c_str(), 1);
    }

    std::filesystem::path root_;
    int run_ = 0;
};

}  // namespace surfscatter::bench
