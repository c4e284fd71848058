// surfscatter psd: radial PSD P(zeta) (sigma^2-mass over the angular-frequency plane, um^4) of a statistics model.
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "statistics_options.hpp"

namespace surfscatter::cli {
namespace {

struct PsdArgs {
    StatisticsOptions model;
    std::string zeta;
};

const Command command("psd", [](CLI::App& app) {
    auto args = std::make_shared<PsdArgs>();
    CLI::App* cmd = app.add_subcommand("psd", "Print the radial PSD P(zeta) (um^4) as CSV zeta,psd; zeta in rad/um");
    args->model.add_to(*cmd);
    cmd->add_option("--zeta", args->zeta, "angular spatial frequencies z1,z2,... (rad/um)")->required();
    cmd->callback([args] {
        const auto stats = args->model.make();
        const auto zetas = parse_number_list(args->zeta, "--zeta");
        std::printf("zeta,psd\n");
        for (double z : zetas) std::printf("%s,%s\n", format_number(z).c_str(), format_number(stats->psd(z)).c_str());
    });
});

}  // namespace
}  // namespace surfscatter::cli
