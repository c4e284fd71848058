#include "surfscatter/heightmap/line_scan.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace surfscatter::heightmap {

std::size_t LineScan::valid_count() const {
    if (validity.empty()) return size();
    return static_cast<std::size_t>(std::count(validity.begin(), validity.end(), std::uint8_t{1}));
}

std::string line_scan_refusal(const LineScan& scan) {
    return fmt::format(
        "{}: a profile ({}: one line of {} points {:.6g} um apart, {:.6g} um long, {:.4g} % valid), not a height map: "
        "the scattering models need heights over an area (x and y)",
        scan.origin, scan.source.format, scan.size(), scan.spacing_um, scan.length_um(),
        100.0 * static_cast<double>(scan.valid_count()) / static_cast<double>(std::max<std::size_t>(scan.size(), 1)));
}

std::string describe_profile(const LineScan& scan, Form form) {
    return fmt::format("profile: form {}{}, {} points {:.6g} um apart ({:.6g} um long), {:.4g} % valid", to_string(form),
                       form == Form::plane ? " (a least-squares line)" : " (mean)", scan.size(), scan.spacing_um,
                       scan.length_um(),
                       100.0 * static_cast<double>(scan.valid_count()) / static_cast<double>(scan.size()));
}

}  // namespace surfscatter::heightmap
