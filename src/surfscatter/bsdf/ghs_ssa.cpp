#include "surfscatter/bsdf/ghs_ssa.hpp"

namespace surfscatter::bsdf {

std::unique_ptr<GhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::RadialStatistics> stats,
                                      material::Conductor material, SsaForm form, FresnelMode fresnel) {
    GhsSettings settings;
    settings.name = "ghs_ssa";
    settings.fresnel = fresnel;
    settings.normalization = form == SsaForm::energy ? LobeNormalization::albedo : LobeNormalization::none;
    settings.relevant_roughness = form == SsaForm::energy;
    auto core = std::make_shared<FirstOrderCore>(stats, form);
    return std::make_unique<GhsBsdf>(std::move(stats), std::move(core), std::move(material), settings);
}

}  // namespace surfscatter::bsdf
