#pragma once
// Reading the user's input files defensively: a directory, a device (/dev/zero), a file larger than its limit or an
// unreadable one is a surfscatter::Error naming the path and the role of the file, never an exception from the
// standard library, a hang or an exhausted memory.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace surfscatter {

// Size limits of the text inputs (docs/RELIABILITY.md): far beyond any real file of the kind, small enough that a
// wrong file (or a pipe that never ends) fails in well under a second.
inline constexpr std::uint64_t kMaxTextInputBytes = std::uint64_t{256} << 20;

// The whole file as bytes. `what` names the role of the file in messages ("scene file", "OBJ file"). Regular files
// are read; directories, FIFOs, devices and sockets are refused; more than `max_bytes` bytes is an error.
std::string read_input_file(const std::filesystem::path& path, const char* what,
                            std::uint64_t max_bytes = kMaxTextInputBytes);

// Throws Error unless `path` names something that can be read as a file ("<what> <path>: is a directory").
void require_readable_file(const std::filesystem::path& path, const char* what);

// Calls f(line, number) for every line of `text` that holds data, numbered from 1: a trailing '\r' removed, blank
// lines and lines whose first non-blank character is '#' skipped (the rule of the project's CSV inputs).
void for_each_data_line(std::string_view text, const std::function<void(std::string_view line, int number)>& f);

// The whole of `text` (no spaces, no trailing characters) as a number, or nullopt; "nan" and "inf" in any case are
// numbers: the caller decides whether they are allowed.
std::optional<double> to_double(std::string_view text);

}  // namespace surfscatter
