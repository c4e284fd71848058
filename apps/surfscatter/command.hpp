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

// A number as printed or written, with full precision (used by every subcommand that prints numbers); a NaN or an
// infinity is an Error instead.
std::string format_number(double v);

// The one rule for what a command tells the user on stderr besides errors: "surfscatter: <command>: note: <text>", or
// "surfscatter: <command>: warning: <rest>" when the text (a library's note) begins "warning: " (no "note: warning:").
// An empty `command` leaves out "<command>: "; an empty text prints nothing.
void print_note(const std::string& command, const std::string& text);

// Flushes stdout; an Error if anything written to it was lost (a full disk, a closed pipe). main() calls it after
// every command.
void flush_standard_output();

}  // namespace surfscatter::cli
