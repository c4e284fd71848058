#pragma once
// Old spellings that are still accepted (docs/CONVENTIONS.md, "Names") are reported through one handler that the
// front end installs: the CLI prints one line on stderr per distinct message, Python issues a DeprecationWarning.
// Without a handler the message goes to stderr as "surfscatter: warning: <message>".
#include <functional>
#include <string>

namespace surfscatter {

using DeprecationHandler = std::function<void(const std::string& message)>;

// Replaces the handler (an empty one restores the default); returns the previous one.
DeprecationHandler set_deprecation_handler(DeprecationHandler handler);

// Reports that the user wrote an old spelling; `message` says what was written and what to write instead. Whatever
// the handler throws (Python: warnings turned into errors) propagates.
void deprecated(const std::string& message);

}  // namespace surfscatter
