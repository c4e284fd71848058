#include "surfscatter/core/input_file.hpp"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <memory>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"

namespace surfscatter {

namespace fs = std::filesystem;

namespace {

std::string shown(const fs::path& path) { return printable(path.string(), kShownPathChars); }

}  // namespace

void require_readable_file(const fs::path& path, const char* what) {
    std::error_code ec;
    const fs::file_status status = fs::status(path, ec);
    if (ec) {
        if (ec == std::errc::no_such_file_or_directory) fail("{} not found: {}", what, shown(path));
        fail("{} {}: {}", what, shown(path), ec.message());
    }
    switch (status.type()) {
        case fs::file_type::regular: return;
        // A FIFO blocks the open until something writes to it, maybe forever.
        case fs::file_type::fifo: fail("{} {} is a FIFO (named pipe), not a file", what, shown(path));
        case fs::file_type::directory: fail("{} {} is a directory, not a file", what, shown(path));
        default: fail("{} {} is not a regular file (a device or socket)", what, shown(path));
    }
}

std::string read_input_file(const fs::path& path, const char* what, std::uint64_t max_bytes) {
    require_readable_file(path, what);
    std::error_code ec;
    if (const std::uintmax_t size = fs::file_size(path, ec); !ec) {  // a regular file: its size is known up front
        if (size > max_bytes)
            fail("{} {} is larger than the {} this reads (docs/RELIABILITY.md)", what, shown(path),
                 format_bytes(static_cast<double>(max_bytes)));
        require_memory(static_cast<double>(size), fmt::format("reading {} {}", what, shown(path)));
    }
    const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
    if (!file) fail("cannot open {} {}: {}", what, shown(path), std::strerror(errno));
    std::string bytes;
    char buffer[1 << 16];
    while (true) {
        const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
        if (n > 0) {
            if (bytes.size() + n > max_bytes)
                fail("{} {} is larger than the {} this reads (docs/RELIABILITY.md)", what, shown(path),
                     format_bytes(static_cast<double>(max_bytes)));
            bytes.append(buffer, n);
        }
        if (n < sizeof buffer) break;
    }
    if (std::ferror(file.get())) fail("read error on {} {}: {}", what, shown(path), std::strerror(errno));
    return bytes;
}

void for_each_data_line(std::string_view text, const std::function<void(std::string_view line, int number)>& f) {
    int number = 0;
    while (!text.empty()) {
        const std::size_t end = std::min(text.find('\n'), text.size());
        std::string_view line = text.substr(0, end);
        text.remove_prefix(std::min(end + 1, text.size()));
        ++number;
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::size_t first = line.find_first_not_of(" \t");
        if (first != std::string_view::npos && line[first] != '#') f(line, number);
    }
}

std::optional<double> to_double(std::string_view text) {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
    return value;
}

}  // namespace surfscatter
