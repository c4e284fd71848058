// surfscatter: command-line front end. Exit status 0 on success, 2 on bad input (one line on stderr).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "command.hpp"
#include "list_options.hpp"
#include "surfscatter/core/deprecation.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/distributed/session.hpp"

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

// Every number a command prints or writes goes through here: a NaN or infinity is refused (exit 2) instead of
// printed. The commands refuse the inputs that would make one, naming them; this is the net behind them.
void print_note(const std::string& command, const std::string& text) {
    if (text.empty()) return;
    constexpr std::string_view kWarning = "warning: ";
    const bool warning = std::string_view(text).substr(0, kWarning.size()) == kWarning;
    std::fprintf(stderr, "surfscatter: %s%s%s\n", command.empty() ? "" : (command + ": ").c_str(),
                 warning ? "" : "note: ", text.c_str());
}

std::string format_number(double v) {
    if (!std::isfinite(v)) fail("a result is {}: the inputs are outside the range where it is defined", v);
    return fmt::format("{:.10g}", v);
}

namespace {

// CLI11 reads an empty value ("--wavelength ''") as 0 for a number: refuse it for every option and positional.
void refuse_empty_values(CLI::App& app) {
    const CLI::Validator non_empty(
        [](std::string& value) { return value.empty() ? std::string("empty value") : std::string(); }, "NON-EMPTY");
    for (CLI::Option* option : app.get_options())
        if (option->get_items_expected_max() > 0) option->check(non_empty);
    for (CLI::App* sub : app.get_subcommands({})) refuse_empty_values(*sub);
}

// CLI11 answers a misspelt subcommand with "A subcommand is required": name it and list the known ones instead.
void check_subcommand_names(CLI::App& app, int argc, char** argv) {
    CLI::App* current = &app;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.empty() || arg[0] == '-') return;  // options (and their values) follow: CLI11 takes over
        const auto subs = current->get_subcommands({});
        if (subs.empty()) return;
        const auto it = std::find_if(subs.begin(), subs.end(), [&](CLI::App* s) { return s->check_name(arg); });
        if (it == subs.end()) {
            std::vector<std::string> names;
            for (CLI::App* s : subs) names.push_back(s->get_name());
            const std::string where = current == &app ? std::string("surfscatter") : "surfscatter " + current->get_name();
            throw surfscatter::Error(fmt::format("unknown subcommand '{}' of {} (known: {})",
                                                 surfscatter::printable(arg), where, fmt::join(names, ", ")));
        }
        current = *it;
    }
}

}  // namespace

void flush_standard_output() {
    errno = 0;
    const bool flushed = std::fflush(stdout) == 0;
    const int error = errno;
    if (!flushed || std::ferror(stdout))
        fail("could not write the standard output{}", error != 0 ? fmt::format(": {}", std::strerror(error)) : "");
}

}  // namespace surfscatter::cli

int main(int argc, char** argv) {
    CLI::App app{
        "surfscatter: rough-metal appearance from surface statistics and wave-optical scattering theories.\n"
        "Units: wavelengths in nm, surface lengths in micrometres, angles in degrees."};
    app.require_subcommand(1);
    app.set_version_flag("--version", "surfscatter " SURFSCATTER_VERSION);
    // An old spelling is named once per run, however many jobs or models repeat it.
    surfscatter::set_deprecation_handler([](const std::string& message) {
        static std::mutex mutex;
        static std::set<std::string> printed;
        const std::lock_guard lock(mutex);
        if (printed.insert(message).second) std::fprintf(stderr, "surfscatter: warning: %s\n", message.c_str());
    });
    for (auto& [name, setup] : surfscatter::cli::registry()) setup(app);
    surfscatter::cli::check_integer_ranges(app);
    surfscatter::cli::refuse_empty_values(app);
    try {
        surfscatter::cli::check_subcommand_names(app, argc, argv);
        app.parse(argc, argv);
        // Every write is checked, stdout too (docs/RELIABILITY.md): what a command printed may still sit in the
        // buffer, and a full disk or a closed pipe shows only when it is flushed. One place for every command.
        surfscatter::cli::flush_standard_output();
        // A job stopped by Ctrl-C or SIGTERM wrote what it had; its status says it did not finish (128 + signal).
        if (surfscatter::interrupt_requested()) return 128 + surfscatter::interrupt_signal();
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "surfscatter: error: %s\n", surfscatter::printable(e.what(), 400).c_str());
        return 2;
    } catch (const surfscatter::distributed::QuietExit& e) {
        return e.status();  // another MPI rank reported the error
    } catch (const surfscatter::Error& e) {
        // Through printable(): one line, whatever bytes a message quotes.
        std::fprintf(stderr, "surfscatter: error: %s\n",
                     surfscatter::printable(e.what(), surfscatter::kShownMessageChars).c_str());
        return 2;
    } catch (const std::filesystem::filesystem_error& e) {
        // Paths come from the user: a name too long, a permission denied, a file where a directory should be.
        std::fprintf(stderr, "surfscatter: error: %s\n", surfscatter::printable(e.what(), 400).c_str());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "surfscatter: internal error: %s\n",
                     surfscatter::printable(e.what(), surfscatter::kShownMessageChars).c_str());
        return 1;
    }
    return 0;
}
