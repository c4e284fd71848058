#include "scene_defines.hpp"

#include "surfscatter/core/error.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter::cli {

std::map<std::string, std::string> parse_defines(const std::vector<std::string>& items) {
    std::map<std::string, std::string> defines;
    for (const std::string& item : items) {
        const auto eq = item.find('=');
        if (eq == std::string::npos || eq == 0) fail("-D expects name=value, got '{}'", printable(item));
        const std::string name = item.substr(0, eq);
        if (!render::is_parameter_name(name))
            fail("-D {}: a parameter name has letters, digits and '_' only (as $name in the scene)", printable(name));
        if (!defines.emplace(name, item.substr(eq + 1)).second) fail("-D {} is given twice", name);
    }
    return defines;
}

}  // namespace surfscatter::cli
