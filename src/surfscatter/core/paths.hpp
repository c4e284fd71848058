#pragma once
// Locations the library uses outside the user's own paths: the on-disk table cache and the plotting scripts.
#include <filesystem>
#include <string>
#include <vector>

namespace surfscatter {

// $SURFSCATTER_CACHE_DIR, else $XDG_CACHE_HOME/surfscatter, else $HOME/.cache/surfscatter (created on demand).
std::filesystem::path cache_directory();

// This machine's host name (for reports of distributed runs).
std::string host_name();

// Directory holding the matplotlib scripts (scripts/plot of the source tree, or $SURFSCATTER_PLOT_SCRIPTS).
std::filesystem::path plot_script_directory();

// Runs /usr/bin/python3 <plot_script_directory()/script> args...; if it fails, throws Error with the last line the
// script wrote to stderr (scripts/plot/plotting.py: "script: cannot write OUT: reason"), else one naming the script.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace surfscatter
