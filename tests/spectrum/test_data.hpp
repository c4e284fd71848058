#pragma once
// Test helpers for the spectrum, material and CLI tests: the '#'-commented CSV files of ../shared/data (one header
// row, then numbers) and temporary input files.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace surfscatter::test {

inline std::string shared_data(const std::string& relative) { return std::string(SURFSCATTER_SHARED_DATA) + "/" + relative; }

inline std::vector<std::vector<double>> read_shared_csv(const std::string& relative) {
    std::ifstream in(shared_data(relative));
    EXPECT_TRUE(in) << relative;
    std::vector<std::vector<double>> rows;
    bool header = true;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#') continue;
        if (header) { header = false; continue; }
        std::vector<double> row;
        std::stringstream fields(line);
        for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
        rows.push_back(row);
    }
    return rows;
}

// Writes `text` to a new file /tmp/surfscatter_test_XXXXXX<extension> and returns its path (the caller removes it).
inline std::string write_temp_file(const std::string& text, const std::string& extension = "") {
    char path[] = "/tmp/surfscatter_test_XXXXXX";
    const int fd = mkstemp(path);
    if (fd >= 0) close(fd);
    std::string named = path;
    if (!extension.empty()) {
        std::remove(path);
        named += extension;
    }
    std::ofstream(named) << text;
    return named;
}

}  // namespace surfscatter::test
