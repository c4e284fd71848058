#pragma once
// Locations the library uses outside the user's own paths: the on-disk table cache and the plotting scripts.
#include <filesystem>
#include <string>
#include <vector>

namespace surfscatter {

// $SURFSCATTER_CACHE_DIR, else $XDG_CACHE_HOME/surfscatter, else $HOME/.cache/surfscatter (created on demand).
std::filesystem::path cache_directory();

// Directory holding the matplotlib scripts (scripts/plot of the source tree, or $SURFSCATTER_PLOT_SCRIPTS).
std::filesystem::path plot_script_directory();

// Runs /usr/bin/python3 <plot_script_directory()/script> args...; throws Error naming the script if it fails.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace surfscatter
