#pragma once
// CIELAB and the CIEDE2000 colour difference (CIE 142-2001), written out because neither OpenCV nor another
// Debian library exposes it as a plain function. Implementation follows Sharma, Wu & Dalal, "The CIEDE2000
// colour-difference formula: implementation notes, supplementary test data, and mathematical observations",
// Color Res. Appl. 30(1), 2005, and is tested against their 34 published pairs (agreement to 1e-4).
#include <array>

namespace surfscatter::photo {

struct Lab {
    double L = 0.0, a = 0.0, b = 0.0;
};

// CIEDE2000 with the parametric factors kL = kC = kH = 1.
double ciede2000(const Lab& reference, const Lab& sample);

// CIE 1976 L*a*b* of tristimulus XYZ relative to the white `white` (same scale as xyz, e.g. Y_white = 1).
Lab xyz_to_lab(const std::array<double, 3>& xyz, const std::array<double, 3>& white);
std::array<double, 3> lab_to_xyz(const Lab& lab, const std::array<double, 3>& white);

}  // namespace surfscatter::photo
