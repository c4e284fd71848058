#pragma once
// Mitsuba 3 XML scenes (the subset listed in docs/RENDERER.md) plus surfscatter's BSDF plugins.
//
// `defines` are the command line's -D name=value pairs: they replace $name in every attribute value and take
// precedence over <default name=... value=...>. A define the scene never uses is an error (a misspelt name would
// otherwise be ignored without a word), unless `used_parameters` is given: then the names of the defines the scene
// used are added to it and the caller decides (compare-models checks its -D against all its scenes together).
//
// Every error (XML syntax, missing file, unknown plugin or parameter, bad value, text or elements inside a value
// element, empty list items, a library error while building a plugin) is a surfscatter::Error whose message starts
// with "file:line: ". Resources are bounded by the limits below (docs/RELIABILITY.md).
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>

#include "surfscatter/render/scene.hpp"

namespace surfscatter::render {

inline constexpr int kMaxElementDepth = 64;            // nesting of XML elements in one file
inline constexpr int kMaxIncludeDepth = 16;            // <include> inside <include>
inline constexpr int kMaxIncludes = 1024;              // <include> elements read for one scene
inline constexpr std::size_t kMaxSceneListItems = 1'000'000;  // numbers in one attribute (a spectrum table)

// Whether `name` can name a scene parameter ($name, -D name=value): letters, digits and '_' only, at least one.
bool is_parameter_name(std::string_view name);

// How the caller's parameters are named in messages: the CLI's "-D name=value" or Python's "params['name']".
enum class ParameterSyntax { command_line, python };

// `defines` replace the scene's $name parameters (the parameter `model`, the metal's BSDF, is read through
// bsdf::find_model: an old spelling of a scattering model's name becomes its name, with a deprecation note).
std::unique_ptr<Scene> load_scene(const std::filesystem::path& path, const std::map<std::string, std::string>& defines = {},
                                  std::set<std::string>* used_parameters = nullptr,
                                  ParameterSyntax syntax = ParameterSyntax::command_line);

// Same, from XML text; `virtual_path` names it in messages and anchors relative file names.
std::unique_ptr<Scene> load_scene_from_string(const std::string& xml, const std::filesystem::path& virtual_path,
                                              const std::map<std::string, std::string>& defines = {},
                                              std::set<std::string>* used_parameters = nullptr);

}  // namespace surfscatter::render
