#pragma once
// The message of the Error `f` throws, or "no error" (the core tests' way to compare messages whole).
#include <functional>
#include <string>

#include "surfscatter/core/error.hpp"

namespace surfscatter::test {

inline std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "no error";
}

}  // namespace surfscatter::test
