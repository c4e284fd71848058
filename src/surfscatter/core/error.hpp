#pragma once
// The one exception type of the library. Its message is a single line that names the bad value and where it
// came from (parameter name, file:line); the CLI prints it as it is and exits with status 2.
#include <exception>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

namespace surfscatter {

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Throws Error with a fmt-formatted message: fail("gamma must be > 1, got {}", gamma).
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
    throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// The one-line message of an exception for reports: an Error's message (printable, kShownMessageChars), anything
// else prefixed with "internal error: ".
std::string error_message(const std::exception_ptr& error);

// Checks a user-supplied value; `what` names it as the user wrote it ("--sigma", "scene.xml:12 alpha").
void require_finite(double value, const char* what);
void require_positive(double value, const char* what);
void require_non_negative(double value, const char* what);

// Text from a user's file or argument, fit to be quoted in a one-line message: bytes outside printable ASCII
// become \xNN (a binary file never reaches the terminal raw) and text longer than `max_chars` is cut with "...".
std::string printable(std::string_view text, std::size_t max_chars = 60);

// How much of a file name a message shows (printable(path, kShownPathChars)): any real path, not a document
// passed where a path belongs.
inline constexpr std::size_t kShownPathChars = 240;

// How much of a whole message the front ends show: error_message, the CLI and the Python exceptions pass every
// message through printable(message, kShownMessageChars), so that whatever a message quotes, it reaches the
// terminal as one printable line.
inline constexpr std::size_t kShownMessageChars = 2000;

}  // namespace surfscatter
