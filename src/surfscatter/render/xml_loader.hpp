#pragma once
// Mitsuba 3 XML scenes (the subset listed in docs/RENDERER.md) plus surfscatter's BSDF plugins.
//
// `defines` are the command line's -D name=value pairs: they replace $name in every attribute value and take
// precedence over <default name=... value=...>. Every error (XML syntax, missing file, unknown plugin or parameter,
// bad value) is a surfscatter::Error whose message starts with "file:line: ".
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, const std::map<std::string, std::string>& defines = {});

// Same, from XML text; `virtual_path` names it in messages and anchors relative file names.
std::unique_ptr<Scene> load_scene_from_string(const std::string& xml, const std::filesystem::path& virtual_path,
                                              const std::map<std::string, std::string>& defines = {});

}  // namespace surfscatter::render
