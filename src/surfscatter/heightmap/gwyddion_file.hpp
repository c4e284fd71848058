#pragma once
// Height maps through Gwyddion's file modules (libgwyddion 2.62: about 159 formats, Debian packages gwyddion and
// libgwyddion20-dev). gwyddion_file.cpp is the only file that includes Gwyddion or GLib headers.
//
// Headless: gwy_widgets_type_init(), the module directories from gwy_app_settings_get_module_dirs(), the
// "plugin-proxy" module (external plug-in programs) disabled, gwy_module_register_modules(); no gtk_init and no
// display. Files are loaded with gwy_file_load_with_func(..., GWY_RUN_NONINTERACTIVE, ...): modules that need a
// dialog (raw data imports) refuse and report an error; none is ever run interactively. Gwyddion is not
// thread-safe: every call holds one process-wide mutex. GLib warnings the modules print while loading are
// captured into HeightMapSource::warnings instead of going to stderr.
#include <cstddef>
#include <filesystem>
#include <string>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// Name of the Gwyddion file module that recognises the file by its content ("metropro", "opdfile", ...), or "".
std::string gwyddion_detect(const std::filesystem::path& path);

// Loads the file with the module that recognises it and returns its first height channel: the lowest-numbered
// image channel whose lateral and height units are metres. Gwyddion's mask of that channel (1 = masked) and any
// non-finite value mark invalid points. Error (naming the module and Gwyddion's message) if no module loads the
// file or it has no height channel.
HeightMap gwyddion_read(const std::filesystem::path& path);

// Writes the map (heights in m, its invalid points as Gwyddion's mask) as a native Gwyddion .gwy file through the
// "gwyfile" module.
void gwyddion_write_gwy(const HeightMap& map, const std::filesystem::path& path);

// For messages: Gwyddion's version ("2.62") and the number of its modules that load files.
std::string gwyddion_version();
std::size_t gwyddion_loader_count();

}  // namespace surfscatter::heightmap
