#pragma once
// Which options apply to which mode of a command, in one place (docs/RELIABILITY.md, issue 36 class 2): an option
// given where it does not apply is an error naming it, never ignored. A command lists its mode-dependent options in a
// table; an option the table does not list applies to every mode. "Given" is CLI11's count: `--realizations 0` or a
// value equal to the default is given too.
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace surfscatter::cli {

struct OptionScope {
    std::string option;              // as the command spells it: "--seed"
    std::vector<std::string> modes;  // the modes it applies to, as the messages name them: "the statistical mode (--psd)"
    std::string needs = {};          // an option without which it has no effect ("--corr-length-v"), or empty
    std::string why = {};            // what it does without `needs` ("the surface is isotropic")
};

// Whether `option` was given to `cmd` (false for an option the command does not have).
bool option_given(const CLI::App& cmd, const std::string& option);

// Throws Error for the first option of `table` given to `cmd` that does not apply to `mode` ("--seed does not apply to
// one profile (--profile): it applies to the statistical mode (--psd)") or lacks the option it needs ("--lay-angle
// needs --corr-length-v: without it the surface is isotropic").
void require_applicable_options(const CLI::App& cmd, const std::string& mode, const std::vector<OptionScope>& table);

}  // namespace surfscatter::cli
