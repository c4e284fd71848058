#pragma once
// Form removal and height moments of a height map, over its valid points only.
//
// The form is the least-squares polynomial surface of total degree d in x and y (d = 0 mean, 1 plane, 2-4
// poly2-poly4): curved samples (cylinders, spheres, bent sheets) carry a form many times their roughness, and a
// PSD or rms taken without removing it measures the sample's shape. The basis is Legendre polynomials
// P_i(u) P_j(v), i + j <= d, in coordinates scaled to [-1, 1] across the grid, so that the normal equations stay
// well conditioned up to degree 4 on any grid; they are accumulated row by row (each row's x sums, weighted by the
// row's P_j(v)), O(N (d+1)(d+2)/2) for N points. A form the valid points cannot determine (too few of them, or all
// on too few rows or columns) is an Error, not a guess.
#include <string>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

// none: only the mean height is removed (a constant offset is never physical); plane: tilt; polyN: degree N.
enum class Form { none, plane, poly2, poly3, poly4 };

// "none", "plane", "poly2", "poly3", "poly4"; anything else is an Error naming `where` ("--form", a scene line).
Form parse_form(const std::string& name, const std::string& where);
std::string to_string(Form form);
int form_degree(Form form);

// The map minus its least-squares form over the valid points (invalid points stay invalid).
HeightMap remove_form(const HeightMap& map, Form form);

// Moments of the heights about their mean over the valid points (skewness and kurtosis are 0 for a flat map).
struct HeightMoments {
    double rms = 0.0;       // um (ISO 25178 Sq of a form-removed map)
    double skewness = 0.0;  // <h^3> / rms^3 (Ssk)
    double kurtosis = 0.0;  // <h^4> / rms^4 (Sku; 3 for a Gaussian surface)
};
HeightMoments height_moments(const HeightMap& map);

// Root-mean-square height about the least-squares form over the valid points (um). A finite patch misses
// wavelengths longer than itself, so this underestimates the sigma_h of the process the patch was drawn from (see
// kc_fit.hpp).
double rms_height(const HeightMap& map, Form form = Form::plane);

}  // namespace surfscatter::heightmap
