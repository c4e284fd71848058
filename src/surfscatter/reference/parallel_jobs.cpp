#include "surfscatter/reference/parallel_jobs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"

namespace surfscatter::reference {

std::vector<char> run_parallel_jobs(std::size_t count, int threads, const std::string& progress_label, bool progress,
                                    const std::function<std::function<void(std::size_t)>()>& make_worker) {
    require_thread_count(threads, "threads");
    const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
    const std::size_t pool_size =
        std::min(count, static_cast<std::size_t>(threads == 0 ? hardware : static_cast<unsigned>(threads)));
    std::vector<char> done(count, 0);
    std::atomic<std::size_t> next{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    Progress bar(progress_label, count, progress);
    const auto work = [&] {
        try {
            const auto job = make_worker();
            for (;;) {
                const std::size_t j = next.fetch_add(1);
                if (j >= count || interrupt_requested()) return;
                {
                    std::lock_guard<std::mutex> lock(error_mutex);
                    if (error) return;
                }
                job(j);
                done[j] = 1;
                bar.advance();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(error_mutex);
            if (!error) error = std::current_exception();
        }
    };
    {
        std::vector<std::thread> pool;
        for (std::size_t t = 1; t < pool_size; ++t) pool.emplace_back(work);
        work();
        for (auto& thread : pool) thread.join();
    }
    if (error) std::rethrow_exception(error);
    bar.finish();
    return done;
}

}  // namespace surfscatter::reference
