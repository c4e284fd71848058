#pragma once
// "SSA GHS": the smooth-surface approximation of the GHS, a single first-order lobe (THEORY 1.4), with the GHS's
// coherent specular delta R(theta_i) e^{-g0} kept so that a smooth surface stays a mirror.
//  energy form (default): f_r = F K1(theta_i) (1 - e^{-g}) k^2 P-hat(zeta), g with sigma_rel, where K1 makes the
//    directional albedo exactly R (scatter R (1 - e^{-g0}) plus delta R e^{-g0}), like the full GHS's K. For lobes
//    narrow compared with the visible disc K1 -> sigma_h^2 / sigma_rel^2 = 1 / M_disc(theta_i) (the wave_tracer /
//    HP17 renormaliser); the plain 1/M_disc form exceeds albedo 1 at grazing incidence (g(theta_o) > g0 there).
//  strict form: f_r = F (4 pi^2 / lambda^4)(cos theta_i + cos theta_o)^2 PSD_f(f) = F k^2 g_h P-hat(zeta),
//    g_h with sigma_h, no renormalisation: the textbook first-order term, which is not energy bounded for large g.
// F follows --fresnel exactly as in the full GHS. On elliptical statistics the same lobe through AnisotropicGhsBsdf.
#include <memory>

#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"

namespace surfscatter::bsdf {

// The SSA's name, Fresnel factor and normalisation (energy: K1 and sigma_rel; strict: none and sigma_h).
GhsSettings ssa_settings(SsaForm form, FresnelMode fresnel);

std::unique_ptr<GhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::RadialStatistics> stats,
                                      material::Conductor material, SsaForm form, FresnelMode fresnel);
class AnisotropicGhsBsdf;
std::unique_ptr<AnisotropicGhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::EllipticalStatistics> stats,
                                                 material::Conductor material, SsaForm form, FresnelMode fresnel);

}  // namespace surfscatter::bsdf
