#pragma once
// What a front end (the CLI's render, Python's render, a study's jobs) passes to a scene besides the user's own
// parameters: the surface a height map implies.
//
// XML has no conditionals, so a scene whose metal reads either statistics or a height map chooses between two files
// by a parameter, `surface` (scenes/photo-setup: surface_$surface.xml, statistics or map). Users give the map alone
// (-D surface_file=PATH): when the scene declares <default name="surface"> and the caller set surface_file but not
// surface, surface=map is added, and surface_file is made absolute against the working directory (a relative path in
// a scene parameter would otherwise be read beside the scene file, Mitsuba's rule for files named in the XML).
#include <filesystem>
#include <map>
#include <string>

namespace surfscatter::render {

// `defines` with the parameters they imply for the scene file `scene` (see above).
std::map<std::string, std::string> implied_scene_parameters(const std::filesystem::path& scene,
                                                            std::map<std::string, std::string> defines);

// The value of a top-level <default name="..." value="..."/> of a scene file; "" when it has none or cannot be read
// (loading the scene reports that).
std::string scene_default(const std::filesystem::path& scene, const std::string& name);

}  // namespace surfscatter::render
