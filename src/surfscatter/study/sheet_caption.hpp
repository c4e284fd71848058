#pragma once
// What a comparison sheet says about each panel: the surface, its roughness in wavelengths, and a warning where the
// panel's model is outside its validity; and how many columns the sheet has.
//
// The roughness is g0 = (4 pi sigma / lambda)^2 at 550 nm and normal incidence (docs/MODELS.md: g0 = g(theta_i,
// theta_i), the exponent of the coherent specular part e^{-g0}). Warnings:
//   * ghs_ssa at g0 > 1: the smooth-surface approximation is first order in g; at g ~ 1-2 its lobe is already far
//     too narrow, and at g0 >> 1 it renders a sharp mirror where the surface is matte;
//   * ggx_stats at g0 < 1: geometric optics has no coherent specular part, which carries e^{-g0} of the light.
#include <cstddef>
#include <filesystem>
#include <string>

#include "surfscatter/study/study.hpp"

namespace surfscatter::study {

struct PanelCaption {
    std::string surface;  // "sigma 0.15 um, g0 11.7", or "" when sigma is not known
    std::string warning;  // "" when the model is within its validity (or it is not known)
};

inline constexpr double kCaptionWavelengthNm = 550.0;

// `parameters`: the render's scene parameters (model, sigma, ...); `scene`: its scene file, whose top-level
// <default name="sigma"> gives sigma when the parameters do not. With a surface_file the caption names the map.
PanelCaption panel_caption(const Parameters& parameters, const std::filesystem::path& scene);

// Columns of a sheet of `panels` panels: `requested` if positive, else all in one row up to 4, else rows of at most 4
// as even as they can be (5 -> 3 + 2, 8 -> 4 + 4, 9 -> 3 x 3).
int sheet_columns(std::size_t panels, int requested);

}  // namespace surfscatter::study
