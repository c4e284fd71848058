#pragma once
// A profile (line scan): heights along one line at a uniform spacing, as a stylus profiler (Dektak OPDx) or a
// profile export (.hfm) stores it. The scattering models need an areal map, so read_height_map() refuses a profile
// with one line saying what the file holds (line_scan_refusal); the readers still read and check it whole, so the
// message states the file's own figures.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/height_map.hpp"

namespace surfscatter::heightmap {

struct LineScan {
    double spacing_um = 0.0;                 // > 0
    std::vector<double> heights_um;          // invalid points hold 0
    std::vector<std::uint8_t> validity;      // 1 = valid, one per point (empty: all valid)
    HeightMapSource source;                  // format, reader, channel, height unit as for a map
    std::string origin;                      // the file

    std::size_t size() const { return heights_um.size(); }
    std::size_t valid_count() const;
    // From the first point to the last.
    double length_um() const { return spacing_um * static_cast<double>(size() - 1); }
};

// "<file>: a profile (<format>: one line of N points 0.5 um apart, 4799.5 um long, 100 % valid), not a height map:
// the scattering models need heights over an area (x and y)".
std::string line_scan_refusal(const LineScan& scan);

// How a profile is prepared (its form only, none or plane), as every front end states it: "profile: form plane (a
// least-squares line), <N> points <d> um apart (<length> um long), <v> % valid".
std::string describe_profile(const LineScan& scan, Form form);

}  // namespace surfscatter::heightmap
