#include "surfscatter/study/sheet_caption.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

#include <fmt/format.h>

#include "surfscatter/render/scene_parameters.hpp"

namespace surfscatter::study {

PanelCaption panel_caption(const Parameters& parameters, const std::filesystem::path& scene) {
    const auto get = [&](const std::string& key) {
        const auto it = parameters.find(key);
        return it != parameters.end() ? it->second : render::scene_default(scene, key);
    };
    PanelCaption caption;
    // A height map gives the surface (render/scene_parameters.hpp); its roughness is known once it is prepared.
    if (const auto map = parameters.find("surface_file"); map != parameters.end()) {
        caption.surface = "height map " + std::filesystem::path(map->second).filename().string();
        return caption;
    }
    const std::string sigma_text = get("sigma");
    char* end = nullptr;
    const double sigma = std::strtod(sigma_text.c_str(), &end);
    if (sigma_text.empty() || *end != '\0' || !(sigma > 0.0) || !std::isfinite(sigma)) return caption;
    const double k_sigma = 4.0 * std::numbers::pi * sigma * 1e3 / kCaptionWavelengthNm;
    const double g0 = k_sigma * k_sigma;
    caption.surface = fmt::format("sigma {:g} um, g0 {:.3g} at {:g} nm", sigma, g0, kCaptionWavelengthNm);
    const std::string model = get("model");
    if ((model == "ghs_ssa" || model == "ghs-ssa") && g0 > 1.0)
        caption.warning = fmt::format("SSA outside its validity (g0 {:.3g} > 1): far too sharp", g0);
    else if ((model == "ggx_stats" || model == "ggx") && g0 < 1.0)
        caption.warning = fmt::format("GGX outside its validity (g0 {:.2g} < 1): no specular part", g0);
    return caption;
}

int sheet_columns(std::size_t panels, int requested) {
    if (requested > 0) return requested;
    const int n = static_cast<int>(std::max<std::size_t>(panels, 1));
    if (n <= 4) return n;
    const int rows = (n + 3) / 4;
    return (n + rows - 1) / rows;
}

}  // namespace surfscatter::study
