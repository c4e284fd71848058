#pragma once
// Options shared by `surfscatter psd` and `surfscatter acv`: the statistics model (--model kc|gaussian, --sigma,
// --corr-length, --gamma) and a comma-separated list of abscissae.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::cli {

struct StatisticsOptions {
    std::string model = "kc";
    double sigma = 0, corr_length = 0;
    std::optional<double> gamma;

    void add_to(CLI::App& cmd);
    std::unique_ptr<surface::RadialStatistics> make() const;  // throws Error naming the bad option
};

// Adds a subcommand that prints CSV "<x>,<value>" for a list given as --<x> x1,x2,...: `value(stats, x)`.
using StatisticsFunction = double (*)(const surface::RadialStatistics&, double);
void add_statistics_table_command(CLI::App& app, const std::string& name, const std::string& description,
                                  const std::string& x_name, const std::string& x_help, const std::string& value_name,
                                  StatisticsFunction value);

}  // namespace surfscatter::cli
