#include "surfscatter/material/refractive_index.hpp"

#include <filesystem>

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/lorentz_drude.hpp"
#include "surfscatter/material/refractiveindex_info.hpp"
#include "surfscatter/material/tabulated_index.hpp"

namespace surfscatter::material {

std::vector<std::string> builtin_metal_names() {
    std::vector<std::string> names;
    for (const auto& p : rakic1998_lorentz_drude()) names.push_back(p.name);
    return names;
}

std::shared_ptr<const RefractiveIndex> load_refractive_index(const std::string& name_or_path) {
    for (const auto& p : rakic1998_lorentz_drude())
        if (p.name == name_or_path) return std::make_shared<LorentzDrudeIndex>(p);
    const std::filesystem::path path(name_or_path);
    const std::string extension = path.extension().string();
    if (extension == ".yml" || extension == ".yaml") return load_refractiveindex_info_yaml(name_or_path);
    if (extension == ".csv") return load_csv_refractive_index(name_or_path);
    fail("unknown material '{}' (built-in: {}; or a refractiveindex.info .yml or a wavelength_nm,n,k .csv file)",
         printable(name_or_path, kShownPathChars), fmt::join(builtin_metal_names(), ", "));
}

}  // namespace surfscatter::material
