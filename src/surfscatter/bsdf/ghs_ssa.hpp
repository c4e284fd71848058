#pragma once
// "SSA GHS": the smooth-surface approximation of the GHS, a single first-order lobe (THEORY 1.4), with the GHS's
// coherent specular delta R(theta_i) e^{-g0} kept so that a smooth surface stays a mirror.
//  energy form (default): f_r = F (1 - e^{-g}) k^2 P-hat(zeta) / M_disc(theta_i),  g with sigma_rel;
//    its albedo is ~R(1 - e^{-g0}) (exact for lobes narrow compared with the visible disc), the wave_tracer-style
//    single lobe but renormalised to the disc of the actual incidence (THEORY 2.1) instead of the normal one.
//  strict form: f_r = F (4 pi^2 / lambda^4)(cos theta_i + cos theta_o)^2 PSD_f(f) = F k^2 g_h P-hat(zeta),
//    g_h with sigma_h, no renormalisation: the textbook first-order term, which is not energy bounded for large g.
// F follows --fresnel exactly as in the full GHS.
#include <memory>

#include "surfscatter/bsdf/ghs.hpp"

namespace surfscatter::bsdf {

std::unique_ptr<GhsBsdf> make_ghs_ssa(std::shared_ptr<const surface::RadialStatistics> stats,
                                      material::Conductor material, SsaForm form, FresnelMode fresnel);

}  // namespace surfscatter::bsdf
