#pragma once
#include <string>

namespace surfscatter::reference {

// How the caller's interface spells the options of the reference solvers (exact-1d, the Kirchhoff map) and of the
// validity studies built on them, for every message that names one (a bad value, the node bound, the memory refusal
// and their remedies): the CLI commands pass their option names (`surfscatter validity` says --wavelengths, `reference exact-1d`
// --wavelength), Python its keywords; the defaults are plain words. An empty name is a setting the caller does not
// offer (Python's fixed points per wavelength): a remedy leaves it out.
struct OptionNames {
    std::string length = "profile";
    std::string wavelength = "wavelength";
    std::string points_per_wavelength = "points per wavelength";
    std::string threads = "threads";
    std::string beam_width = "beam width";
    std::string material = "material";
    std::string realizations = "realizations";
    // validity's criteria (validity::require_valid_criteria)
    std::string tolerance = "tolerance", bin_deg = "bin width", max_reference_stderr = "reference's largest standard error";
    std::string subarea = "sub-area side";  // the Kirchhoff map's
};

}  // namespace surfscatter::reference
