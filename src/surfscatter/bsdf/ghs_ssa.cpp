#include "surfscatter/bsdf/ghs_ssa.hpp"

#include "surfscatter/bsdf/anisotropic_ghs.hpp"

namespace surfscatter::bsdf {

GhsSettings ssa_settings(SsaForm form, FresnelMode fresnel) {
    GhsSettings settings;
    settings.name = "ghs_ssa";
    settings.fresnel = fresnel;
    settings.normalization = form == SsaForm::energy ? LobeNormalization::albedo : LobeNormalization::none;
    settings.relevant_roughness = form == SsaForm::energy;
    return settings;
}

std::unique_ptr<GhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::RadialStatistics> stats,
                                      material::Conductor material, SsaForm form, FresnelMode fresnel) {
    auto core = std::make_shared<FirstOrderCore>(stats, form);
    return std::make_unique<GhsBsdf>(std::move(stats), std::move(core), std::move(material),
                                     ssa_settings(form, fresnel));
}

std::unique_ptr<AnisotropicGhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::EllipticalStatistics> stats,
                                                 material::Conductor material, SsaForm form, FresnelMode fresnel) {
    auto core = std::make_shared<FirstOrderCore>(stats->radial_ptr(), form);
    return std::make_unique<AnisotropicGhsBsdf>(std::move(stats), std::move(core), std::move(material),
                                                ssa_settings(form, fresnel));
}

}  // namespace surfscatter::bsdf
