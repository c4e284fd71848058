#pragma once
// Outliers of a height map: isolated points far from their neighbours (dust on the sample, an interferometer's
// unwrapping errors or drop-outs), which no model of the surface's statistics describes. A few of them can hold most
// of a map's pixel-scale roughness: they raise its PSD at high frequencies (where their squared height counts) and its
// Kirchhoff BRDF (where their phase saturates) by different amounts, so models and reference then disagree about the
// outliers, not the surface (docs/HEIGHTMAPS.md "Outliers"; the Zygo file of docs/VALIDITY.md).
//
// Detection, on residuals that a plane (so slope and form) does not reach, at the map's edges neither: with the pairs
// of valid points symmetric about a point, the linear residual r = h - the mean of the midpoints of its 3 x 3 pairs (a
// linear filter: Gaussian for a Gaussian surface) and the local one r' = h - the median of the midpoints of its 5 x 5
// pairs (a spike's neighbours keep theirs; widened along an edge until there are 5 pairs); s = 1.4826 x the median
// absolute deviation of r over the points tested; an outlier wherever |r| > kOutlierThreshold s and |r'| >
// kOutlierThreshold s. For a Gaussian surface r exceeds 8 s with probability 1e-15 per point; no point is flagged on KC
// and Gaussian maps of 2-50 pixels a correlation length (the test below), where a plain 5 x 5 median residual flagged
// thousands on the smooth ones. A point with fewer than 5 pairs (a corner and the points next to it along the edges) is
// not tested. A real surface with sharp features (pits, scratches, grooves) can have points flagged, which is why
// keeping them is the default and filling is asked for. share: the outliers' part of sum r^2, the map's pixel-scale
// roughness; above kDominantOutlierShare the outliers, not the surface, decide what the map scatters at large angles.
// Filling: each outlier takes the median of the midpoints of its 5 x 5 pairs of valid non-outliers (the neighbourhood
// widened one pixel at a time until it holds 5 pairs), as Gwyddion's spot removal interpolates from the
// surroundings.
// Measured (tests/heightmap/test_height_map_outliers.cpp): no false alarm on those maps; spikes put on one found exactly,
// and the filled map within 3.5 robust sigma of the map without them at every spike.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

inline constexpr double kOutlierThreshold = 8.0;       // robust standard deviations of the residual
inline constexpr double kDominantOutlierShare = 0.5;   // of sum r^2

// What to do with them where a map is read for the models or a reference (--outliers, XML and Python `outliers`).
enum class OutlierPolicy { keep, fill };
OutlierPolicy parse_outlier_policy(const std::string& name, const std::string& where);  // "keep" | "fill"
std::string to_string(OutlierPolicy policy);

struct Outliers {
    std::vector<std::uint8_t> mask;  // 1 at an outlier, per point (ny rows of nx); empty when there are none
    std::size_t count = 0;           // points
    std::size_t spots = 0;           // connected groups of them (8-neighbour)
    double robust_sigma_um = 0;      // s above
    double largest_um = 0;           // largest |r'| of an outlier (its height over its surroundings)
    double share = 0;                // of sum r^2 over the valid points
    bool dominant() const { return share > kDominantOutlierShare; }
};

// Whether a map's statistics describe its outliers rather than its surface: they were kept and they dominate.
inline bool kept_and_dominant(const Outliers& outliers, OutlierPolicy policy) {
    return policy == OutlierPolicy::keep && outliers.dominant();
}

Outliers find_outliers(const HeightMap& map);
// The map with every outlier replaced as above (invalid points stay invalid); the map itself when there are none.
HeightMap fill_outliers(const HeightMap& map, const Outliers& outliers);
// find_outliers, and with policy fill the map filled: what the readers of a map for the models and the references
// do. `found` gets the outliers (its mask cleared).
HeightMap apply_outlier_policy(HeightMap map, OutlierPolicy policy, Outliers& found);
// One line: how many, where they stand against the robust sigma, the largest, their share.
std::string describe(const Outliers& outliers);
// The same with what `policy` did with them and, kept, what they do to the map's statistics.
std::string describe(const Outliers& outliers, OutlierPolicy policy);
// The line the models' notes and the CLI give for the map named `name`: "[warning: ]<name>: <describe(.., policy)>",
// a warning when they are kept and dominate.
std::string outliers_note(const std::string& name, const Outliers& outliers, OutlierPolicy policy);

}  // namespace surfscatter::heightmap
