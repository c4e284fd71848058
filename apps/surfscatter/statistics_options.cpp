#include "statistics_options.hpp"

#include <cstdio>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

void StatisticsOptions::add_to(CLI::App& cmd) {
    cmd.add_option("--model", model, "kc (K-correlation) or gaussian (Gaussian ACV)");
    cmd.add_option("--sigma", sigma, "rms height sigma_h (um)")->required();
    cmd.add_option("--corr-length", corr_length, "correlation length (um)")->required();
    cmd.add_option("--gamma", gamma, "KC exponent gamma > 1 (--model kc)");
}

std::unique_ptr<surface::RadialStatistics> StatisticsOptions::make() const {
    surface::require_surface_length(sigma, "--sigma");
    surface::require_surface_length(corr_length, "--corr-length");
    if (model == "kc") {
        if (!gamma) fail("--gamma is required for --model kc");
        surface::require_kc_gamma(*gamma, "--gamma");
        return std::make_unique<surface::KCorrelation>(sigma, corr_length, *gamma);
    }
    if (model == "gaussian") {
        if (gamma) fail("--gamma applies to --model kc only");
        return std::make_unique<surface::GaussianAcv>(sigma, corr_length);
    }
    fail("--model must be kc or gaussian, got '{}'", model);
}

void add_statistics_table_command(CLI::App& app, const std::string& name, const std::string& description,
                                  const std::string& x_name, const std::string& x_help, const std::string& value_name,
                                  StatisticsFunction value) {
    struct Args {
        StatisticsOptions model;
        std::vector<double> xs;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(name, description);
    args->model.add_to(*cmd);
    const std::string flag = "--" + x_name;
    add_number_list(cmd, flag, args->xs, x_help)->required();
    cmd->callback([args, flag, x_name, value_name, value] {
        const auto stats = args->model.make();
        for (double x : args->xs)
            if (x < 0) fail("{}: {} must be >= 0", flag, x);
        std::printf("%s,%s\n", x_name.c_str(), value_name.c_str());
        for (double x : args->xs) std::printf("%s,%s\n", format_number(x).c_str(), format_number(value(*stats, x)).c_str());
    });
}

}  // namespace surfscatter::cli
