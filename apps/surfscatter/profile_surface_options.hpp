#pragma once
// The surface options --psd kc|gaussian --sigma --corr-length [--gamma] of exact-1d's statistical mode, models-1d
// and validity: the isotropic statistics the random profiles are cuts through.
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "surfscatter/surface/radial_statistics.hpp"

namespace surfscatter::cli {

struct SurfaceArgs {
    std::optional<std::string> psd;
    std::optional<double> sigma, corr_length, gamma;
    void add_to(CLI::App* sub, const char* psd_help);
};

// Throws Error naming the missing or bad option; `psd` must be set.
std::unique_ptr<surface::RadialStatistics> statistics_from(const SurfaceArgs& a);

}  // namespace surfscatter::cli
