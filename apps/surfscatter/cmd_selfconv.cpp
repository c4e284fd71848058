// surfscatter selfconv: self-convolutions of the unit-mass KC PSD and the supplemental's refit L_m = L m^-x
// (THEORY.md 2.4): prints "x = <value>" and a CSV m,L_m,misfit; --plot reproduces the supplemental's Fig. 2.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <memory>

#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/output_files.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/surface/refit.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"

namespace surfscatter::cli {
namespace {

struct SelfconvArgs {
    double gamma = 0, corr_length = 0;
    int orders = 0;
    std::string out, plot;
};

std::string table_csv(const surface::RefitResult& fit) {
    std::string out = "m,L_m,misfit\n";
    for (std::size_t i = 0; i < fit.corr_length_m.size(); ++i)
        out += fmt::format("{},{},{}\n", i + 1, format_number(fit.corr_length_m[i]), format_number(fit.misfit_m[i]));
    return out;
}

// Curves for the figure: P-hat^{*m} and its refit for a few orders, on a log zeta grid.
std::string curves_csv(const surface::KCorrelation& kc, const surface::RefitResult& fit, int orders) {
    const auto table = surface::SelfConvolutionTable::get(kc, orders);
    std::vector<int> shown;
    for (int m : {1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377, 610, 987})
        if (m <= orders) shown.push_back(m);
    std::ostringstream out;
    out << "zeta";
    for (int m : shown) out << ",true_" << m << ",fit_" << m;
    out << '\n';
    const double l = kc.correlation_length();
    for (int j = 0; j <= 240; ++j) {
        const double z = 1e-2 / l * std::pow(10.0, j / 40.0);
        out << format_number(z);
        for (int m : shown) {
            const surface::KCorrelation refit(1.0, fit.corr_length_m[m - 1], kc.gamma());
            out << ',' << format_number(table->eval(m, z)) << ',' << format_number(refit.psd_unit(z));
        }
        out << '\n';
    }
    return out.str();
}

void run(const SelfconvArgs& args) {
    const std::string base = std::filesystem::path(args.plot).replace_extension("").string();
    const std::string curves = base + "_curves.csv", table = base + "_table.csv";
    OutputFiles files;
    if (!args.out.empty()) files.output(args.out, "--out");
    if (!args.plot.empty()) {
        files.output(args.plot, "--plot");
        files.output(curves, "--plot's curves CSV");
        files.output(table, "--plot's table CSV");
    }
    surface::require_kc_gamma(args.gamma, "--gamma");
    surface::require_surface_length(args.corr_length, "--corr-length");
    surface::require_refit_orders(args.orders, "--orders");
    const surface::KCorrelation kc(1.0, args.corr_length, args.gamma);
    const surface::RefitResult fit = surface::refit_self_convolutions(kc, args.orders);
    std::printf("x = %s\n", format_number(fit.exponent_x).c_str());
    std::fputs(table_csv(fit).c_str(), stdout);
    if (!args.out.empty()) files.write(args.out, table_csv(fit));
    if (!args.plot.empty()) {
        files.write(curves, curves_csv(kc, fit, args.orders));
        files.write(table, table_csv(fit));
        files.write_with(args.plot, [&](const std::filesystem::path& png) {
            run_plot_script("selfconv.py", {files.staged(curves).string(), files.staged(table).string(), png.string(),
                                            fmt::format("KC self-convolutions, gamma = {:g}, L = {:g} um: x = {:.4f}",
                                                        args.gamma, args.corr_length, fit.exponent_x)});
        });
    }
    files.commit();
    if (!args.out.empty())
        std::fprintf(stderr, "surfscatter: selfconv: wrote %s\n", printable_path(args.out).c_str());
    if (!args.plot.empty())
        std::fprintf(stderr, "surfscatter: selfconv: wrote %s (data: %s, %s)\n", printable_path(args.plot).c_str(),
                     printable_path(curves).c_str(), printable_path(table).c_str());
}

const Command command("selfconv", [](CLI::App& app) {
    auto args = std::make_shared<SelfconvArgs>();
    CLI::App* cmd = app.add_subcommand(
        "selfconv", "Self-convolutions of the KC PSD, refit L_m = L m^-x: prints 'x = ...' and CSV m,L_m,misfit");
    cmd->add_option("--gamma", args->gamma, "KC exponent gamma > 1")->required();
    cmd->add_option("--corr-length", args->corr_length, "correlation length L (um)")->required();
    cmd->add_option("--orders", args->orders, "highest order M (1..5000)")->required();
    cmd->add_option("--out", args->out, "also write the m,L_m,misfit table to this CSV file");
    cmd->add_option("--plot", args->plot, "write the supplemental's Fig. 2 (convolved PSDs, inset L_m) as PNG");
    cmd->callback([args] { run(*args); });
});

}  // namespace
}  // namespace surfscatter::cli
