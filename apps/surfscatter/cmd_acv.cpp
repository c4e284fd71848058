// surfscatter acv: autocovariance C(r) (um^2) of a statistics model.
#include "command.hpp"
#include "statistics_options.hpp"

namespace surfscatter::cli {
namespace {

const Command command("acv", [](CLI::App& app) {
    add_statistics_table_command(
        app, "acv", "Print the autocovariance C(r) (um^2) as CSV r,acv; r in um", "r", "lateral distances r1,r2,... (um)",
        "acv", [](const surface::RadialStatistics& s, double r) { return s.acv(r); });
});

}  // namespace
}  // namespace surfscatter::cli
