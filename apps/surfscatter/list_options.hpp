#pragma once
// Comma-separated list options (--wavelength 400,500,600, --models ggx,ghs). CLI11's own delimiter drops empty
// items, so "400,,500" would silently be read as two wavelengths: these parse the list themselves and reject an
// empty item, an item with a control character (a line break), a non-number, and more than kMaxListItems items
// (core/resources.hpp). Each occurrence of the option adds its items.
#include <cstddef>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "surfscatter/core/resources.hpp"  // kMaxListItems

namespace surfscatter::cli {

// Parses "x1,x2,..." of finite numbers; `option` names the flag in errors ("--wavelength: item 2 of '400,,500' is
// empty").
std::vector<double> parse_number_list(const std::string& text, const std::string& option);
std::vector<std::string> parse_string_list(const std::string& text, const std::string& option);

// CLI11 reads integer options with strtoll / strtoull and keeps the saturated value (--seed 99999999999999999999
// became 9223372036854775807; -5 for an unsigned option wrapped around): this range-checks every integer option and
// positional of `app` and its subcommands, in one place (main calls it once). Values beyond the 64-bit range and
// negative values of unsigned options are errors naming the option and the value.
void check_integer_ranges(CLI::App& app);

CLI::Option* add_number_list(CLI::App* cmd, const std::string& name, std::vector<double>& values,
                             const std::string& help);
CLI::Option* add_string_list(CLI::App* cmd, const std::string& name, std::vector<std::string>& values,
                             const std::string& help);

}  // namespace surfscatter::cli
