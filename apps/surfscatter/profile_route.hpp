#pragma once
// Profiles (.hfm exports, Dektak OPDx line scans) where a map is expected: `surface info | fit` report the profile's
// own statistics, and `brdf --surface` gives the areal models, under the assumption of isotropy stated as a note,
// the profile's own spectrum (--psd measured, the default: surface::ProfileStatistics, the inverse Abel transform of
// its 1-D PSD) or the KC fitted to its 1-D PSD (--psd file), which needs a knee within the profile's band
// (surface/profile_statistics.hpp; docs/HEIGHTMAPS.md "Profiles").
#include <optional>
#include <string>

#include "preparation_options.hpp"
#include "surfscatter/heightmap/line_scan.hpp"
#include "surfscatter/surface/profile_statistics.hpp"

namespace surfscatter::cli {

// The profile `path` holds, or nullopt if it is not a profile file. A profile is prepared by its form only: any other
// preparation option, a --form other than none or plane, or a --spacing / --height-unit contradicting the file is
// an Error naming it.
std::optional<heightmap::LineScan> read_profile(const std::string& path, const PreparationArgs& preparation,
                                                std::optional<double> spacing_um = std::nullopt,
                                                std::optional<double> height_unit_um = std::nullopt);

// The form --form asks for on a profile (default plane: a least-squares line).
heightmap::Form profile_form(const PreparationArgs& preparation);

// The fit the areal models use, resolved (its failure an Error), with the note they print.
struct ProfileSurface {
    surface::ProfileFit fit;
    std::string note;
};
ProfileSurface profile_surface(const heightmap::LineScan& scan, heightmap::Form form);

}  // namespace surfscatter::cli
