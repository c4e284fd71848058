#include "statistics_options.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "command.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

void StatisticsOptions::add_to(CLI::App& cmd) {
    cmd.add_option("--model", model, "kc (K-correlation) or gaussian (Gaussian ACV)");
    cmd.add_option("--sigma", sigma, "rms height sigma_h (um)")->required();
    cmd.add_option("--corr-length", corr_length, "correlation length (um)")->required();
    cmd.add_option("--gamma", gamma, "KC exponent gamma > 1 (--model kc)");
}

std::unique_ptr<surface::RadialStatistics> StatisticsOptions::make() const {
    require_positive(sigma, "--sigma");
    require_positive(corr_length, "--corr-length");
    if (model == "kc") {
        if (!gamma) fail("--gamma is required for --model kc");
        require_finite(*gamma, "--gamma");
        if (!(*gamma > 1.0)) fail("--gamma must be > 1 (the KC variance is infinite otherwise), got {}", *gamma);
        return std::make_unique<surface::KCorrelation>(sigma, corr_length, *gamma);
    }
    if (model == "gaussian") {
        if (gamma) fail("--gamma applies to --model kc only");
        return std::make_unique<surface::GaussianAcv>(sigma, corr_length);
    }
    fail("--model must be kc or gaussian, got '{}'", model);
}

std::vector<double> parse_number_list(const std::string& text, const char* option) {
    std::vector<double> values;
    std::size_t start = 0;
    while (true) {
        const std::size_t comma = text.find(',', start);
        const std::string token = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(token.c_str(), &end);
        if (token.empty() || end != token.c_str() + token.size() || errno == ERANGE)
            fail("{}: '{}' is not a number (expected a comma-separated list)", option, token);
        if (!std::isfinite(v) || v < 0.0) fail("{}: {} must be finite and >= 0", option, token);
        values.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return values;
}

void add_statistics_table_command(CLI::App& app, const std::string& name, const std::string& description,
                                  const std::string& x_name, const std::string& x_help, const std::string& value_name,
                                  StatisticsFunction value) {
    struct Args {
        StatisticsOptions model;
        std::string list;
    };
    auto args = std::make_shared<Args>();
    CLI::App* cmd = app.add_subcommand(name, description);
    args->model.add_to(*cmd);
    const std::string flag = "--" + x_name;
    cmd->add_option(flag, args->list, x_help)->required();
    cmd->callback([args, flag, x_name, value_name, value] {
        const auto stats = args->model.make();
        const auto xs = parse_number_list(args->list, flag.c_str());
        std::printf("%s,%s\n", x_name.c_str(), value_name.c_str());
        for (double x : xs) std::printf("%s,%s\n", format_number(x).c_str(), format_number(value(*stats, x)).c_str());
    });
}

}  // namespace surfscatter::cli
