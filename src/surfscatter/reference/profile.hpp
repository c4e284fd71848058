#pragma once
// A 1-D surface profile z = h(x), invariant along y: uniformly spaced heights in um (docs/REFERENCE.md).
#include <cstddef>
#include <string>
#include <vector>

namespace surfscatter::reference {

// Heights are limited like a height map's (heightmap/height_map.hpp): squares and sums stay finite.
inline constexpr double kMaxProfileHeightUm = 1e9;
inline constexpr std::size_t kMinProfileSamples = 4;

struct Profile {
    double x0_um = 0.0;          // abscissa of the first sample
    double spacing_um = 0.0;     // x_{j+1} - x_j, > 0
    std::vector<double> h_um;    // heights, at least kMinProfileSamples
    double x_end_um() const { return x0_um + spacing_um * static_cast<double>(h_um.size() - 1); }
};

// Throws Error naming `what` unless the profile has enough finite samples, a positive spacing and bounded heights.
void require_valid_profile(const Profile& profile, const std::string& what);

// CSV with the header `x_um,h_um` and one row per sample, x increasing with a uniform step (to 1e-6 of the step,
// relative to the largest |x|); lines starting with '#' and blank lines are skipped. Errors name path:line.
Profile read_profile_csv(const std::string& path);
Profile parse_profile_csv(const std::string& text, const std::string& path);
std::string format_profile_csv(const Profile& profile);

// Heights and their first two derivatives at the nodes x0 + j spacing/m (j = 0 .. (n-1) m) of a natural cubic spline
// through the samples: the solver's surface (interpolation error ~ spacing^4 h''''/384).
struct SplineNodes {
    double x0_um = 0.0, step_um = 0.0;
    std::vector<double> h, dh, d2h;
};
SplineNodes spline_nodes(const Profile& profile, std::size_t subdivisions);

}  // namespace surfscatter::reference
