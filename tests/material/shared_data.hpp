#pragma once
// Reads the '#'-commented CSV files of ../shared/data (one header row, then numbers).
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

}  // namespace surfscatter::test
