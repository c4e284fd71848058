#include "surfscatter/core/resources.hpp"

#include <unistd.h>

#include <fstream>
#include <string>

#include "surfscatter/core/error.hpp"

namespace surfscatter {

void require_thread_count(long long threads, const char* what) {
    if (threads < 0 || threads > kMaxThreads)
        fail("{} must be between 1 and {} (or 0 for all cores), got {}", what, kMaxThreads, threads);
}

void require_list_size(std::size_t items, const char* what) {
    if (items > kMaxListItems) fail("{}: {} items, more than {}", what, items, kMaxListItems);
}

std::uint64_t available_memory_bytes() {
    std::ifstream meminfo("/proc/meminfo");
    for (std::string key; meminfo >> key;) {
        std::uint64_t kib = 0;
        if (key == "MemAvailable:" && meminfo >> kib) return kib * 1024;
        meminfo.ignore(256, '\n');
    }
    // No /proc: free physical pages.
    const long pages = sysconf(_SC_AVPHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
    return pages > 0 && page_size > 0 ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size)
                                      : UINT64_MAX;
}

std::string format_bytes(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    int unit = 0;
    while (bytes >= 1024.0 && unit < 6) {
        bytes /= 1024.0;
        ++unit;
    }
    return fmt::format("{:.4g} {}", bytes, units[unit]);
}

void require_memory(double bytes, const std::string& what) {
    const auto available = static_cast<double>(available_memory_bytes());
    if (!(bytes <= available))
        fail("{} needs {} of memory, more than the {} available", what, format_bytes(bytes), format_bytes(available));
}

}  // namespace surfscatter
