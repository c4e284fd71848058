#pragma once
// Progress reporting for long jobs: percentage and ETA on stderr, safe to call from many threads. A bar redrawn in
// place when stderr is a terminal; otherwise (a log file, a pipe) a line when it starts ("render: started") and the
// final one, without carriage returns.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace surfscatter {

bool stderr_is_terminal();  // whether progress is drawn as a bar

class Progress {
public:
    // `total` work units; `label` is printed before the bar. Silent when `enabled` is false.
    Progress(std::string label, std::uint64_t total, bool enabled = true);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    void advance(std::uint64_t units = 1);  // thread-safe; redraws at most ~10 times a second
    void finish();                           // prints the final line (idempotent)
    double fraction() const;
    std::uint64_t done() const { return done_.load(); }  // units advanced so far

private:
    void draw(bool final_line);

    std::string label_;
    std::uint64_t total_;
    bool enabled_;
    bool terminal_;  // stderr is a terminal
    std::atomic<std::uint64_t> done_{0};
    std::chrono::steady_clock::time_point start_;
    std::chrono::steady_clock::time_point last_draw_;
    std::mutex draw_mutex_;
    bool finished_ = false;
};

// Formats seconds as "1h02m", "3m05s" or "12.3s".
std::string format_duration(double seconds);

// Ctrl-C handling for jobs that must keep what they computed: after install_interrupt_handler(), the first
// SIGINT/SIGTERM/SIGUSR1 sets a flag that long loops poll with interrupt_requested(); they stop early and write out.
// A second signal of the same kind ends the process (default action).
void install_interrupt_handler();
bool interrupt_requested();
int interrupt_signal();  // the signal that interrupted (SIGINT, SIGTERM, SIGUSR1), 0 if none
void clear_interrupt();  // for tests
void request_interrupt();  // for tests: behave as if Ctrl-C had been pressed

}  // namespace surfscatter
