#pragma once
// Whether the Kirchhoff (tangent-plane) reference of a height map (reference/kirchhoff_map.hpp) can be trusted at a
// wavelength and incidence. The tangent-plane approximation replaces the surface at each point by its tangent plane,
// so it needs (Tsang, Kong et al., "Scattering of Electromagnetic Waves", the tangent-plane approximation for a rough
// surface: radius of curvature >> lambda, shadowing and multiple scattering negligible; [M] in THEORY.md 7.4's sense):
// * a local radius of curvature rho large against the wavelength: 2 k rho cos^3(theta_i) >> 1 (Brekhovskikh's
//   condition, [M]); taken here as rho cos^3(theta_i) >= lambda (2 k rho cos^3 >= 4 pi) at all but
//   kMaxCurvatureShare of the valid pixels;
// * k l >= kMinKl with l the map's 1/e correlation length (surface::acv_measures, the azimuthal mean): Thorsos 1988
//   (THEORY.md 7.4, [M]) found Kirchhoff accurate against the exact 1-D solution for Gaussian surfaces from k l
//   about 6 on, and failing below whatever the height;
// * no shadowing (and no multiple scattering): at most kMaxShadowedShare of the valid pixels in the shadow of the
//   incident light.
// The curvature and the shadows are those of the map smoothed by a Gaussian of standard deviation 1 / k (normalised
// over valid points): spatial frequencies above 2 k scatter into no propagating direction at first order (the
// Kirchhoff lattice ends at |q_xy| < 2 k) and are attenuated by e^-2 or more, so pixel noise does not decide.
// Curvature: the largest principal curvature |H| + sqrt(H^2 - K) of z = h(x, y) from central differences (second
// order in the pixel spacing; on a sinusoid of 64 pixels a period the median radius within 1 % and the share of
// pixels curved under lambda within 1.5 % of the closed form, KirchhoffValidity tests).
// Shadows: a pixel is shadowed when the map rises above the ray towards the light, marched in steps of the smaller
// pixel spacing with bilinear heights until the ray passes the map's highest point or leaves the map (or its valid
// points); on a triangle wave of slope s within 2 pixels of a brute-force search on the closed form and within the
// last period of the infinite wave's s / (s + cot theta_i) (KirchhoffValidity tests).
#include <string>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::validity {

inline constexpr double kMinKl = 6.0;
inline constexpr double kMaxCurvatureShare = 0.05;
inline constexpr double kMaxShadowedShare = 0.05;

struct KirchhoffValidity {
    double k_l = 0;                   // k times the map's 1/e correlation length
    double curvature_share = 0;       // of valid pixels with rho cos^3(theta_i) < lambda
    double median_radius_um = 0;      // median local radius of curvature rho
    double shadowed_share = 0;        // of valid pixels shadowed at the incidence
    bool valid = false;               // all three criteria hold
    std::string text;                 // what holds and what fails, one line
};

// `flat`: the map with its form removed. Throws Error for a bad wavelength or incidence.
KirchhoffValidity kirchhoff_validity(const heightmap::HeightMap& flat, double lambda_nm, double theta_i_deg,
                                     double phi_i_deg);

// The map smoothed by a Gaussian of standard deviation `sigma_um`, normalised over the valid points (exposed for the
// tests' closed-form checks).
heightmap::HeightMap smooth_map(const heightmap::HeightMap& map, double sigma_um);

// Share of the valid pixels of `map` in the shadow of light from (theta_i, phi_i) (header).
double shadowed_share(const heightmap::HeightMap& map, double theta_i_deg, double phi_i_deg);

}  // namespace surfscatter::validity
