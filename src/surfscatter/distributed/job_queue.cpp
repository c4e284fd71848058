#include "surfscatter/distributed/job_queue.hpp"

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"

namespace surfscatter::distributed {

namespace {

constexpr auto kPollInterval = std::chrono::milliseconds(2);

// Which jobs may run next: bookkeeping only, on rank 0.
class Dispatcher {
public:
    Dispatcher(const std::vector<std::vector<int>>& dependencies, const std::vector<bool>& done,
               const JobCallbacks& callbacks)
        : dependencies_(dependencies), state_(dependencies.size(), State::waiting), callbacks_(callbacks) {
        if (done.size() != dependencies.size()) fail("run_jobs: {} done flags for {} jobs", done.size(), dependencies.size());
        for (std::size_t i = 0; i < dependencies.size(); ++i) {
            if (done[i]) state_[i] = State::finished;
            // Dependencies on earlier jobs only: no cycles, and the first waiting job is always ready.
            for (const int d : dependencies[i])
                if (d < 0 || static_cast<std::size_t>(d) >= i)
                    fail("run_jobs: job {} depends on job {}, which is not an earlier job", i, d);
        }
    }

    std::optional<int> next() {
        for (; first_waiting_ < state_.size() && state_[first_waiting_] != State::waiting; ++first_waiting_) {}
        for (std::size_t i = first_waiting_; i < state_.size(); ++i) {
            if (state_[i] != State::waiting || !ready(i)) continue;
            state_[i] = State::running;
            ++running_;
            return static_cast<int>(i);
        }
        return std::nullopt;
    }

    void finish(int job, const std::string& report, int rank) {
        callbacks_.finished(job, report, rank);
        state_[static_cast<std::size_t>(job)] = State::finished;
        --running_;
    }

    int running() const { return running_; }

private:
    enum class State { waiting, running, finished };

    bool ready(std::size_t job) const {
        for (const int d : dependencies_[job])
            if (state_[static_cast<std::size_t>(d)] != State::finished) return false;
        return true;
    }

    const std::vector<std::vector<int>>& dependencies_;
    std::vector<State> state_;
    const JobCallbacks& callbacks_;
    std::size_t first_waiting_ = 0;
    int running_ = 0;
};

// A request: "<finished job or -1>\n<its report>".
std::string encode_request(int job, const std::string& report) { return std::to_string(job) + "\n" + report; }

std::pair<int, std::string> decode_request(const std::string& text) {
    const auto newline = text.find('\n');
    if (newline == std::string::npos) fail("malformed job request '{}'", text.substr(0, 80));
    return {std::stoi(text.substr(0, newline)), text.substr(newline + 1)};
}

constexpr int kStop = -1;

std::string run_guarded(const Session& session, const JobCallbacks& callbacks, int job) {
    try {
        return callbacks.run(job);
    } catch (...) {
        session.abort(fmt::format("job {}: {}", job, error_message(std::current_exception())));
    }
}

// Rank 0's own worker and the handing-out thread meet here.
struct LocalChannel {
    std::mutex mutex;
    std::condition_variable assigned;
    bool asking = true;           // the worker waits for a job
    int finished_job = -1;        // with the report of the job it just finished
    std::string report;
    std::optional<int> assignment;
};

void run_in_process(const std::vector<std::vector<int>>& dependencies, const std::vector<bool>& done,
                    const JobCallbacks& callbacks) {
    Dispatcher dispatcher(dependencies, done, callbacks);
    while (!interrupt_requested()) {
        const std::optional<int> job = dispatcher.next();
        if (!job) break;
        dispatcher.finish(*job, callbacks.run(*job), 0);  // an exception here ends the one process anyway
    }
}

void hand_out(const Session& session, Dispatcher& dispatcher, LocalChannel& local) {
    std::deque<int> asking;  // ranks waiting for an answer
    int stopped = 0;
    while (stopped < session.size()) {
        while (auto message = session.poll(Tag::job_request)) {
            auto [job, report] = decode_request(message->payload);
            if (job >= 0) dispatcher.finish(job, report, message->source);
            asking.push_back(message->source);
        }
        {
            std::lock_guard lock(local.mutex);
            if (local.asking && !local.assignment) {
                if (local.finished_job >= 0) dispatcher.finish(local.finished_job, local.report, 0);
                local.finished_job = -1;
                local.asking = false;
                asking.push_back(0);
            }
        }
        for (std::size_t n = asking.size(); n > 0; --n) {
            const int rank = asking.front();
            asking.pop_front();
            std::optional<int> answer;
            if (!interrupt_requested()) {
                if (auto job = dispatcher.next()) answer = *job;
            }
            // Without a job now, a rank waits while some job runs (its dependents may become ready), else stops.
            if (!answer && !interrupt_requested() && dispatcher.running() > 0) {
                asking.push_back(rank);
                continue;
            }
            const int assignment = answer.value_or(kStop);
            if (assignment == kStop) ++stopped;
            if (rank == 0) {
                std::lock_guard lock(local.mutex);
                local.assignment = assignment;
                local.assigned.notify_one();
            } else {
                session.send(rank, Tag::job_assignment, std::to_string(assignment));
            }
        }
        std::this_thread::sleep_for(kPollInterval);
    }
}

}  // namespace

void run_jobs(const Session& session, const std::vector<std::vector<int>>& dependencies, const std::vector<bool>& done,
              const JobCallbacks& callbacks) {
    if (session.size() == 1) {
        run_in_process(dependencies, done, callbacks);
        return;
    }
    if (session.root()) {
        std::optional<Dispatcher> dispatcher;
        LocalChannel local;
        std::exception_ptr error;
        std::thread handing_out([&] {
            try {
                dispatcher.emplace(dependencies, done, callbacks);
                hand_out(session, *dispatcher, local);
            } catch (...) {
                error = std::current_exception();
                std::lock_guard lock(local.mutex);
                local.assignment = kStop;
                local.assigned.notify_one();
            }
        });
        for (;;) {
            int job = kStop;
            {
                std::unique_lock lock(local.mutex);
                local.assigned.wait(lock, [&] { return local.assignment.has_value(); });
                job = *local.assignment;
            }
            if (job == kStop) break;
            std::string report = run_guarded(session, callbacks, job);
            std::lock_guard lock(local.mutex);
            local.assignment.reset();
            local.finished_job = job;
            local.report = std::move(report);
            local.asking = true;
        }
        handing_out.join();
        if (error) session.abort(error_message(error));
    } else {
        int finished = -1;
        std::string report;
        for (;;) {
            session.send(0, Tag::job_request, encode_request(finished, report));
            const Message answer = session.receive(0, Tag::job_assignment);
            const int job = std::stoi(answer.payload);
            if (job == kStop) break;
            report = run_guarded(session, callbacks, job);
            finished = job;
        }
    }
    session.wait_for_all();
}

}  // namespace surfscatter::distributed
