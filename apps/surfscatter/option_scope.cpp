#include "option_scope.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

// A command may lack some of a shared table's options (calibrate has no grid boards): those are not given.
bool option_given(const CLI::App& cmd, const std::string& name) {
    const CLI::Option* option = cmd.get_option_no_throw(name);
    return option != nullptr && option->count() > 0;
}

void require_applicable_options(const CLI::App& cmd, const std::string& mode, const std::vector<OptionScope>& table) {
    for (const OptionScope& scope : table) {
        if (!option_given(cmd, scope.option)) continue;
        if (std::find(scope.modes.begin(), scope.modes.end(), mode) == scope.modes.end())
            fail("{} does not apply to {}: it applies to {}", scope.option, mode, fmt::join(scope.modes, " and "));
        if (!scope.needs.empty() && !option_given(cmd, scope.needs))
            fail("{} needs {}: without it {}", scope.option, scope.needs, scope.why);
    }
}

}  // namespace surfscatter::cli
