#pragma once
// A measured map as metrology prepares it, once, for every consumer (the models, the references, `surface info | fit`,
// scenes, studies, Python): outliers kept or filled, rows aligned, the form removed, then ISO 16610-61's S- and
// L-filters. docs/HEIGHTMAPS.md "Preparation" states each step, its default and why. What every statistic then reads
// is `PreparedMap::map`, whose form is already removed (statistics take it with Form::none, which removes the mean
// only); what the L-filter removed is the waviness, kept beside it.
#include <optional>
#include <string>
#include <vector>

#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/height_map.hpp"
#include "surfscatter/heightmap/gaussian_filter.hpp"
#include "surfscatter/heightmap/outliers.hpp"
#include "surfscatter/heightmap/rows.hpp"

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

// The shortest period the default L-filter may take for waviness (um): a period Lambda turns light of wavelength
// lambda by about lambda / Lambda from the specular direction, and at the renderer's longest wavelength (1 um) a
// period of 100 um or more turns it by at most 0.6 deg, within a lamp's or a camera pixel's angular size: it tilts the
// surface locally rather than scattering. Shorter periods are the BRDF's own and are never removed by default
// (docs/HEIGHTMAPS.md "Preparation").
inline constexpr double kShortestWavinessUm = 100.0;

// The options of a map's preparation, named alike at the CLI (--outliers, --row-alignment, --form, --lambda-s,
// --lambda-c), in XML and studies (outliers, row_alignment, form, lambda_s, lambda_c) and in Python (outliers,
// row_alignment, form, lambda_s_um, lambda_c_um).
struct Preparation {
    OutlierPolicy outliers = OutlierPolicy::keep;
    RowAlignment rows = RowAlignment::automatic;
    Form form = Form::plane;
    double lambda_s_um = 0;               // S-filter nesting index; 0: none
    std::optional<double> lambda_c_um;    // L-filter nesting index; unset: default_lambda_c() from 100 um; 0: none
    auto operator<=>(const Preparation&) const = default;
};

// "auto" (unset), "none" (0) or a nesting index in um for --lambda-c; "none" (0) or um for --lambda-s. Error naming
// `where` for anything else (a negative, non-finite or unparsable value).
std::optional<double> parse_lambda_c(const std::string& text, const std::string& where);
double parse_lambda_s(const std::string& text, const std::string& where);

struct PreparedMap {
    HeightMap map;                // what every statistic reads: outliers as asked, rows aligned, form removed, filtered
    Preparation applied;          // the options as applied (lambda_c_um set: the default resolved)
    Outliers outliers;            // found on the map as read (without the mask): filled, or kept
    RowOffsets rows;              // found and, if applied.rows says so or they are significant, removed
    bool rows_aligned = false;
    std::string lambda_c_reason;  // why the default L-filter is what it is (empty when lambda_c was given)
    std::optional<HeightMap> waviness;  // what the L-filter removed (periods beyond lambda_c), form-free
    double read_rms_um = 0;       // rms of the map as read about its mean (valid points)
    double form_rms_um = 0;       // rms of the form removed
    double short_rms_um = 0;      // rms of what the S-filter removed
    double waviness_rms_um = 0;   // rms of the waviness
};

// The one preparation of a map read from a file or made in memory.
PreparedMap prepare(const HeightMap& map, const Preparation& how);

// One line for every output that reports on a map: the steps in order with what each removed.
std::string describe(const PreparedMap& prepared);

}  // namespace surfscatter::heightmap
