#pragma once
// Finite resources of the machine, checked before a job allocates or starts threads, so that a huge request is one
// clear error line instead of std::bad_alloc, an OOM kill or a crash inside a threading library. The limits are
// listed in docs/RELIABILITY.md.
#include <cstddef>
#include <cstdint>
#include <string>

namespace surfscatter {

// Worker threads accepted by every --threads option. Past a few hundred threads the TBB arena aborts in its
// destructor; no machine this runs on has more cores.
inline constexpr int kMaxThreads = 256;

// Throws Error naming `what` unless 0 <= threads <= kMaxThreads (0 means all hardware threads).
void require_thread_count(long long threads, const char* what);

// Items of one list a user gives (CLI lists such as --wavelengths, Python's wavelengths_nm, theta_o_deg): far beyond
// any real use, a bound on the cases a job is asked for before it starts (docs/RELIABILITY.md).
inline constexpr std::size_t kMaxListItems = 100'000;

// Throws Error "<what>: 1000000 items, more than 100000" if `items` exceeds kMaxListItems.
void require_list_size(std::size_t items, const char* what);

// Bytes of memory the system can give this process now (MemAvailable of /proc/meminfo).
std::uint64_t available_memory_bytes();

// Throws Error "<what> needs 7.3 TiB of memory, more than the 6.1 GiB available" if `bytes` exceeds the memory
// available now. `bytes` is a double so that products of huge sizes cannot wrap around.
void require_memory(double bytes, const std::string& what);

// "12.3 GiB", "512 MiB", "7.276 TiB" (4 significant digits).
std::string format_bytes(double bytes);

}  // namespace surfscatter
