#pragma once
// Independent jobs 0..count-1 (random profiles, sub-areas) on a few threads, with a progress bar and Ctrl-C: the
// references' one way of running in parallel.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace surfscatter::reference {

// Each thread calls make_worker() once (for its own state, e.g. an FFT plan) and then the function it returns on the
// jobs it takes. Threads: 0 = all cores, never more than the jobs. No job starts once interrupt_requested() is set
// or a job has thrown; the first exception is rethrown after every thread has stopped. Returns 1 for each job done.
std::vector<char> run_parallel_jobs(std::size_t count, int threads, const std::string& progress_label, bool progress,
                                    const std::function<std::function<void(std::size_t)>()>& make_worker);

}  // namespace surfscatter::reference
