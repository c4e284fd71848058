#include "profile_route.hpp"

#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/io.hpp"

namespace surfscatter::cli {

heightmap::Form profile_form(const PreparationArgs& preparation) {
    return preparation.form ? heightmap::parse_form(*preparation.form, "--form") : heightmap::Form::plane;
}

std::optional<heightmap::LineScan> read_profile(const std::string& path, const PreparationArgs& preparation,
                                                std::optional<double> spacing_um, std::optional<double> height_unit_um) {
    std::optional<heightmap::LineScan> scan = heightmap::read_line_scan(path);
    if (!scan) return scan;
    for (const auto& [option, value] : {std::pair{"--outliers", &preparation.outliers},
                                        std::pair{"--row-alignment", &preparation.row_alignment},
                                        std::pair{"--lambda-s", &preparation.lambda_s},
                                        std::pair{"--lambda-c", &preparation.lambda_c}})
        if (*value)
            fail("{}: {} applies to areal maps; a profile is prepared by its form only (--form none | plane)", path,
                 option);
    const heightmap::Form form = profile_form(preparation);
    if (form != heightmap::Form::none && form != heightmap::Form::plane)
        fail("{}: --form {} on a profile: a profile's form is none (its mean) or plane (a least-squares line)", path,
             heightmap::to_string(form));
    if (spacing_um && std::abs(*spacing_um - scan->spacing_um) > 1e-6 * scan->spacing_um)
        fail("{}: --spacing {} um contradicts the file, which states {} um ({})", path, *spacing_um, scan->spacing_um,
             scan->source.format);
    if (height_unit_um && std::abs(*height_unit_um - scan->source.height_unit_um) > 1e-9 * scan->source.height_unit_um)
        fail("{}: --height-unit {} um contradicts the file, which states its heights in units of {} um ({})", path,
             *height_unit_um, scan->source.height_unit_um, scan->source.format);
    return scan;
}

ProfileSurface profile_surface(const heightmap::LineScan& scan, heightmap::Form form) {
    surface::KcFitOptions options;
    options.form = form;
    ProfileSurface out{surface::fit_profile(scan, options), ""};
    surface::require_resolved(out.fit.kc);
    out.note = fmt::format("{}: {}; the areal models use KC sigma_h {:.6g} um, L_c {:.6g} um, gamma {:.6g} (the profile's "
                           "rms {:.6g} um)",
                           scan.origin, surface::kIsotropyNote, out.fit.kc.sigma_h_um, out.fit.kc.corr_length_um,
                           out.fit.kc.gamma, out.fit.rms_height_um);
    return out;
}

}  // namespace surfscatter::cli
