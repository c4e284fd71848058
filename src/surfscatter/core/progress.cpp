#include "surfscatter/core/progress.hpp"

#include <unistd.h>

#include <csignal>
#include <cstdio>

#include <fmt/format.h>

namespace surfscatter {

namespace {
volatile std::sig_atomic_t g_interrupted = 0;

// The first signal asks the job to stop and write what it has; the default action is restored so that a second
// Ctrl-C ends the process at once if writing takes too long.
extern "C" void on_interrupt(int signal_number) {
    g_interrupted = signal_number;
    std::signal(signal_number, SIG_DFL);
}
}  // namespace

void install_interrupt_handler() {
    std::signal(SIGINT, on_interrupt);
    std::signal(SIGTERM, on_interrupt);
    // mpirun forwards SIGUSR1 to every rank at once (SIGINT reaches the ranks only as a SIGTERM after
    // odls_base_sigkill_timeout); Slurm sends it before a time limit with --signal=USR1@seconds.
    std::signal(SIGUSR1, on_interrupt);
}
bool interrupt_requested() { return g_interrupted != 0; }
int interrupt_signal() { return g_interrupted; }
void clear_interrupt() { g_interrupted = 0; }
void request_interrupt() { g_interrupted = SIGINT; }

bool stderr_is_terminal() { return isatty(fileno(stderr)) == 1; }

std::string format_duration(double seconds) {
    if (!(seconds >= 0.0)) return "--";
    if (seconds < 60.0) return fmt::format("{:.1f}s", seconds);
    auto s = static_cast<long long>(seconds + 0.5);
    if (s < 3600) return fmt::format("{}m{:02}s", s / 60, s % 60);
    return fmt::format("{}h{:02}m", s / 3600, (s % 3600) / 60);
}

Progress::Progress(std::string label, std::uint64_t total, bool enabled)
    : label_(std::move(label)), total_(total == 0 ? 1 : total), enabled_(enabled),
      // A log file or pipe gets the final line only: redrawn bars left a study's log 43 KB of carriage returns.
      terminal_(stderr_is_terminal()), start_(std::chrono::steady_clock::now()), last_draw_(start_) {
    // A log shows what is under way (and a test or a watcher when to act), one line at the start, one at the end.
    if (enabled_ && !terminal_) {
        std::fprintf(stderr, "%s: started\n", label_.c_str());
        std::fflush(stderr);
    }
}

Progress::~Progress() { finish(); }

double Progress::fraction() const {
    return static_cast<double>(done_.load()) / static_cast<double>(total_);
}

void Progress::advance(std::uint64_t units) {
    done_ += units;
    if (!enabled_ || !terminal_) return;
    auto now = std::chrono::steady_clock::now();
    std::unique_lock lock(draw_mutex_, std::try_to_lock);
    if (!lock.owns_lock() || now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    draw(false);
}

void Progress::finish() {
    std::lock_guard lock(draw_mutex_);
    if (finished_ || !enabled_) {
        finished_ = true;
        return;
    }
    finished_ = true;
    draw(true);
}

void Progress::draw(bool final_line) {
    const double f = std::min(1.0, fraction());
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int width = 30;
    const int filled = static_cast<int>(f * width);
    std::string bar(static_cast<size_t>(filled), '#');
    bar.append(static_cast<size_t>(width - filled), '.');
    std::string eta = f > 0.0 ? format_duration(elapsed * (1.0 - f) / f) : std::string("--");
    if (final_line && !terminal_)
        std::fprintf(stderr, "%s: %.1f%% done in %s\n", label_.c_str(), 100.0 * f, format_duration(elapsed).c_str());
    else if (final_line)
        std::fprintf(stderr, "\r%s [%s] %5.1f%% done in %s          \n", label_.c_str(), bar.c_str(),
                     100.0 * f, format_duration(elapsed).c_str());
    else
        std::fprintf(stderr, "\r%s [%s] %5.1f%% elapsed %s ETA %s   ", label_.c_str(), bar.c_str(),
                     100.0 * f, format_duration(elapsed).c_str(), eta.c_str());
    std::fflush(stderr);
}

}  // namespace surfscatter
