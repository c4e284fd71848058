#include "surfscatter/core/deprecation.hpp"

#include <cstdio>
#include <mutex>
#include <utility>

namespace surfscatter {

namespace {
std::mutex g_mutex;
DeprecationHandler g_handler;
}  // namespace

DeprecationHandler set_deprecation_handler(DeprecationHandler handler) {
    std::lock_guard lock(g_mutex);
    return std::exchange(g_handler, std::move(handler));
}

void deprecated(const std::string& message) {
    DeprecationHandler handler;
    {
        std::lock_guard lock(g_mutex);
        handler = g_handler;
    }
    if (handler) handler(message);
    else std::fprintf(stderr, "surfscatter: warning: %s\n", message.c_str());
}

}  // namespace surfscatter
