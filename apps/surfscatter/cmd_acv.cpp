// surfscatter acv: autocovariance C(r) (um^2) of a statistics model.
#include <cstdio>
#include <memory>

#include "command.hpp"
#include "statistics_options.hpp"

namespace surfscatter::cli {
namespace {

struct AcvArgs {
    StatisticsOptions model;
    std::string r;
};

const Command command("acv", [](CLI::App& app) {
    auto args = std::make_shared<AcvArgs>();
    CLI::App* cmd = app.add_subcommand("acv", "Print the autocovariance C(r) (um^2) as CSV r,acv; r in um");
    args->model.add_to(*cmd);
    cmd->add_option("--r", args->r, "lateral distances r1,r2,... (um)")->required();
    cmd->callback([args] {
        const auto stats = args->model.make();
        const auto rs = parse_number_list(args->r, "--r");
        std::printf("r,acv\n");
        for (double r : rs) std::printf("%s,%s\n", format_number(r).c_str(), format_number(stats->acv(r)).c_str());
    });
});

}  // namespace
}  // namespace surfscatter::cli
