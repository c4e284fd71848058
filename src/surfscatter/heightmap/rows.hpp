#pragma once
// Row alignment: a scanning instrument gives each row (x, one scan line) its own height offset, a bright line on the
// zeta_x = 0 axis of the 2-D spectrum. Offsets: running sums of the median differences between neighbouring rows'
// common valid points, minus their cubic in y (a tilt or curvature across the rows is form, left for form removal).
// They also take the surface's own row-mean profile, and a lay along the rows (grooves along x) is constant along
// the rows as offsets are. What tells them apart is the profile across the rows: offsets are white from row to row,
// a surface the instrument resolves (its lay included) is smooth there. So `auto` aligns when (1) the rows' mean
// steps scatter more than the rows' own roughness explains (R) and (2) the row levels' white floor, their spectrum
// across the rows at periods of 2-2.9 rows, exceeds what the rows' own roughness puts there (W); each against
// its floor (kRowOffsetRatio, kWhiteFloorRatio) and its quantile at 1 - kRowOffsetFalseAlarm. What it then removes
// is the levels' white part (a Wiener split of their spectrum against that floor), so a lay is kept; `median`
// removes all of them.
// Derivation, measured false alarms and accuracy: docs/HEIGHTMAPS.md "Row alignment".
#include <cstddef>
#include <string>
#include <vector>

#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

inline constexpr double kRowOffsetRatio = 4.0;        // R above which `auto` may align (the floor of the threshold)
inline constexpr double kRowOffsetFalseAlarm = 1e-4;  // P(R > threshold) for a surface without offsets
inline constexpr double kWhiteFloorRatio = 2.0;        // W above which `auto` may align, once R has said so
inline constexpr double kRowOffsetFalseAlarmZ = 3.719;  // the standard normal's quantile 1 - kRowOffsetFalseAlarm
inline constexpr std::size_t kMinRowOverlap = 8;      // valid points two rows must share to be compared

// none: the map as it is; median: always aligned; automatic ("auto"): aligned when the offsets are significant.
enum class RowAlignment { none, median, automatic };
// "none" | "median" | "auto"; anything else is an Error naming `where` ("--row-alignment", a scene line).
RowAlignment parse_row_alignment(const std::string& name, const std::string& where);
std::string to_string(RowAlignment a);

struct RowOffsets {
    std::vector<double> offset_um;  // per row (ny), the level subtracted from it; 0 on rows with no valid point
    double rms_um = 0;              // rms of the offsets over the rows with valid points
    double ratio = 0;               // R above (0 when it could not be taken)
    double independent_rows = 0;    // nu: the rows' count over their correlation along y
    double threshold = 0;           // max(kRowOffsetRatio, chi^2_nu / nu quantile at 1 - kRowOffsetFalseAlarm)
    double white_ratio = 0;         // W: the levels' floor at periods of 2-2.9 rows over the rows' own (0: not taken)
    double white_threshold = 0;     // max(kWhiteFloorRatio, the quantile of W's median of K bins)
    std::vector<double> white_um;   // per row: the white part of offset_um (what `auto` subtracts)
    double white_rms_um = 0;        // its rms over the rows with valid points
    bool lay = false;               // R > threshold but W is not: a profile across the rows, not offsets
    bool detected = false;          // R > threshold and W > white_threshold
    std::size_t unlinked_rows = 0;  // rows with valid points sharing fewer than kMinRowOverlap with every row above
    std::string reason;             // one line: R, the rows it rests on, and the verdict
};

// The offsets and their significance. Never fails on a valid map; a map with fewer than 8 comparable rows gets
// ratio 0, detected false and the reason.
RowOffsets find_row_offsets(const HeightMap& map);

// The map with its rows aligned: `none` returns it unchanged (found gets an empty offset_um and reason "none");
// `median` subtracts the offsets (all of the levels); `automatic` subtracts their white part when detected. `found`
// gets what find_row_offsets found.
HeightMap align_rows(const HeightMap& map, RowAlignment how, RowOffsets& found);

// One line: what was found and done ("row alignment auto: row levels rms 0.012 um, their white part 0.011 um,
// aligned (their white part removed): R ..., W ...").
std::string describe(const RowOffsets& found, RowAlignment how);

}  // namespace surfscatter::heightmap
