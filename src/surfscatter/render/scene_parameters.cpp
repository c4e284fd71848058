#include "surfscatter/render/scene_parameters.hpp"

#include <pugixml.hpp>

namespace surfscatter::render {

std::string scene_default(const std::filesystem::path& scene, const std::string& name) {
    pugi::xml_document document;
    if (!document.load_file(scene.c_str())) return "";
    for (const pugi::xml_node node : document.child("scene").children("default"))
        if (name == node.attribute("name").value()) return node.attribute("value").value();
    return "";
}

std::map<std::string, std::string> implied_scene_parameters(const std::filesystem::path& scene,
                                                            std::map<std::string, std::string> defines) {
    const auto file = defines.find("surface_file");
    if (file == defines.end() || scene_default(scene, "surface").empty()) return defines;
    if (!file->second.empty()) file->second = std::filesystem::absolute(file->second).lexically_normal().string();
    defines.emplace("surface", "map");  // a surface the caller chose stays
    return defines;
}

}  // namespace surfscatter::render
