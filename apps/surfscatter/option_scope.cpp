#include "option_scope.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"

namespace surfscatter::cli {

void require_applicable_options(const CLI::App& cmd, const std::string& mode, const std::vector<OptionScope>& table) {
    // A command may lack some of a shared table's options (calibrate has no grid boards): those are not given.
    const auto given = [&cmd](const std::string& name) {
        const CLI::Option* option = cmd.get_option_no_throw(name);
        return option != nullptr && option->count() > 0;
    };
    for (const OptionScope& scope : table) {
        if (!given(scope.option)) continue;
        if (std::find(scope.modes.begin(), scope.modes.end(), mode) == scope.modes.end())
            fail("{} does not apply to {}: it applies to {}", scope.option, mode, fmt::join(scope.modes, " and "));
        if (!scope.needs.empty() && !given(scope.needs))
            fail("{} needs {}: without it {}", scope.option, scope.needs, scope.why);
    }
}

}  // namespace surfscatter::cli
