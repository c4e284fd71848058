#pragma once
// Subcommand registry: each cmd_<name>.cpp defines a static `Command` that adds its subcommand to the app.
// A subcommand only parses options, calls the library and prints or writes; errors are surfscatter::Error.
#include <functional>
#include <string>

#include <CLI/CLI.hpp>

namespace surfscatter::cli {

struct Command {
    // `setup` adds the subcommand (with its callback) to the root app.
    Command(std::string name, std::function<void(CLI::App&)> setup);
};

// Prints a CSV header and rows with full precision (used by every subcommand that prints numbers).
std::string format_number(double v);

}  // namespace surfscatter::cli
