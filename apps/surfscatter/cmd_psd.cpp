// surfscatter psd: radial PSD P(zeta) (sigma^2-mass over the angular-frequency plane, um^4) of a statistics model.
#include "command.hpp"
#include "statistics_options.hpp"

namespace surfscatter::cli {
namespace {

const Command command("psd", [](CLI::App& app) {
    add_statistics_table_command(
        app, "psd", "Print the radial PSD P(zeta) (um^4) as CSV zeta,psd; zeta in rad/um", "zeta",
        "angular spatial frequencies z1,z2,... (rad/um)", "psd",
        [](const surface::RadialStatistics& s, double zeta) { return s.psd(zeta); });
});

}  // namespace
}  // namespace surfscatter::cli
