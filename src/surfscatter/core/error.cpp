#include "surfscatter/core/error.hpp"

#include <cmath>

namespace surfscatter {

void require_finite(double value, const char* what) {
    if (!std::isfinite(value)) fail("{} must be a finite number, got {}", what, value);
}

void require_positive(double value, const char* what) {
    if (!(value > 0.0) || !std::isfinite(value)) fail("{} must be positive, got {}", what, value);
}

void require_non_negative(double value, const char* what) {
    if (!(value >= 0.0) || !std::isfinite(value)) fail("{} must be >= 0, got {}", what, value);
}

std::string printable(std::string_view text, std::size_t max_chars) {
    std::string out;
    std::size_t shown = 0;
    for (const char c : text) {
        if (shown == max_chars) {
            out += "...";
            break;
        }
        const auto byte = static_cast<unsigned char>(c);
        if (byte >= 0x20 && byte < 0x7f) out += c;
        else out += fmt::format("\\x{:02x}", byte);
        ++shown;
    }
    return out;
}

std::string error_message(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const Error& e) {
        return printable(e.what(), kShownMessageChars);
    } catch (const std::exception& e) {
        return "internal error: " + printable(e.what(), kShownMessageChars);
    } catch (...) {
        return "internal error: unknown exception";
    }
}

}  // namespace surfscatter
