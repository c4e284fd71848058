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

// A temporary name beside `file` that no other process or host uses, keeping the extension (tools pick the format
// from it): folder/.stem.tmp-<host>-<pid>.ext. Written and then renamed over `file`, it makes the write atomic:
// readers - other processes, other hosts on a shared file system - see the old file or the new, never part of one.
std::filesystem::path temporary_beside(const std::filesystem::path& file);

// Writes `text` to `file` that way; throws Error naming the file if it cannot.
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

// Directory holding the matplotlib scripts (scripts/plot of the source tree, or $SURFSCATTER_PLOT_SCRIPTS).
std::filesystem::path plot_script_directory();

// Runs /usr/bin/python3 <plot_script_directory()/script> args...; if it fails, throws Error with the last line the
// script wrote to stderr (scripts/plot/plotting.py: "script: cannot write OUT: reason"), else one naming the script.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace surfscatter
