// surfscatter: command-line front end. Exit status 0 on success, 2 on bad input (one line on stderr).
#include <algorithm>
#include <cstdio>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

namespace {
std::map<std::string, std::function<void(CLI::App&)>>& registry() {
    static std::map<std::string, std::function<void(CLI::App&)>> commands;
    return commands;
}
}  // namespace

Command::Command(std::string name, std::function<void(CLI::App&)> setup) {
    registry().emplace(std::move(name), std::move(setup));
}

std::string format_number(double v) { return fmt::format("{:.10g}", v); }

}  // namespace surfscatter::cli

int main(int argc, char** argv) {
    CLI::App app{
        "surfscatter: rough-metal appearance from surface statistics and wave-optical scattering theories.\n"
        "Units: wavelengths in nm, surface lengths in micrometres, angles in degrees."};
    app.require_subcommand(1);
    app.set_version_flag("--version", "surfscatter 0.1.0");
    for (auto& [name, setup] : surfscatter::cli::registry()) setup(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "surfscatter: error: %s\n", e.what());
        return 2;
    } catch (const surfscatter::Error& e) {
        std::fprintf(stderr, "surfscatter: error: %s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfscatter: internal error: %s\n", e.what());
        return 1;
    }
    return 0;
}
