#pragma once
// A measured map as metrology prepares it, once, for every consumer (the models, the references, `surface info | fit`,
// scenes, studies, Python): outliers kept or filled, then the form removed. docs/HEIGHTMAPS.md "Preparation" states
// each step, its default and why. What every statistic then reads is `PreparedMap::map`, whose form is already
// removed (statistics take it with Form::none, which removes the mean only).
#include <string>
#include <vector>

#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/outliers.hpp"

namespace surfscatter::heightmap {

// Wrap-around test: a map is periodic when the mean square jump across each pair of opposite edges is at most this
// many times the mean square step between neighbours along the same axis (a periodic random field gives 1 within
// its scatter; an instrument's map, whose opposite edges are unrelated, gives about 2 sigma^2 / step^2 >> 1).
inline constexpr double kPeriodicJumpRatio = 3.0;

// Mean square jump across opposite edges over mean square neighbour step, the larger of the two axes (see
// kPeriodicJumpRatio), of a map without invalid points, as measured (differences do not see its mean): a plane fitted
// to a periodic map raises it (measured 0.84 -> 2.3, poly2 4.0 on a 1024^2 Gaussian-ACV map 55 l wide); the real
// instrument files give 50 to 10^4.
double wrap_jump_ratio(const HeightMap& map);

// Whether a map wraps around seamlessly (no invalid points, wrap_jump_ratio() <= kPeriodicJumpRatio): the statistics'
// window rule (surface/map_statistics.hpp). Judged on the data as read, before any form removal (a form fitted to a
// periodic map is noise that would break it): a prepared map says what prepare() judged (source.periodic).
bool is_periodic(const HeightMap& map);

// The options of a map's preparation, named alike at the CLI (--outliers, --form), in XML and in Python.
struct Preparation {
    OutlierPolicy outliers = OutlierPolicy::keep;
    Form form = Form::plane;
    auto operator<=>(const Preparation&) const = default;
};

struct PreparedMap {
    HeightMap map;          // what every statistic reads: outliers as asked, form removed
    Preparation applied;    // the options as applied
    Outliers outliers;      // found on the map as read (without the mask): filled, or kept
    double read_rms_um = 0; // rms of the map as read about its mean (valid points)
    double form_rms_um = 0; // rms of the form removed
};

// The one preparation of a map read from a file or made in memory.
PreparedMap prepare(const HeightMap& map, const Preparation& how);

// One line for every output that reports on a map: the steps in order with what each removed.
std::string describe(const PreparedMap& prepared);

}  // namespace surfscatter::heightmap
