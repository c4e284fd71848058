#include "study_runner.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/distributed/job_queue.hpp"
#include "surfscatter/study/jobs.hpp"
#include "surfscatter/study/manifest.hpp"
#include "surfscatter/study/run_job.hpp"

namespace surfscatter::cli {

namespace {

using nlohmann::json;

constexpr int kInterrupted = 130;

// Which jobs need not run: up to date themselves and in everything they read; a tables job when every job that
// waits for it need not run.
std::vector<bool> up_to_date(const std::vector<study::Job>& jobs, const study::Manifest& manifest) {
    std::vector<bool> done(jobs.size(), false);
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        if (jobs[i].kind == study::JobKind::tables) continue;
        bool ok = manifest.up_to_date(jobs[i]);
        for (const int d : jobs[i].dependencies)
            if (jobs[static_cast<std::size_t>(d)].kind != study::JobKind::tables) ok = ok && done[static_cast<std::size_t>(d)];
        done[i] = ok;
    }
    std::vector<bool> needed(jobs.size(), false);
    for (std::size_t i = 0; i < jobs.size(); ++i)
        if (!done[i])
            for (const int d : jobs[i].dependencies) needed[static_cast<std::size_t>(d)] = true;
    for (std::size_t i = 0; i < jobs.size(); ++i)
        if (jobs[i].kind == study::JobKind::tables) done[i] = !needed[i];
    return done;
}

}  // namespace

void add_study_run_options(CLI::App* command, StudyRunOptions& options) {
    command->add_option("--threads", options.threads, "Worker threads per rank, 1..256 (default 0: all the rank's cores)");
    command->add_flag("--quiet", options.quiet, "No render progress bars");
    command->add_flag("--list", options.list, "List the jobs and which are up to date; run nothing");
}

void run_study(const std::function<study::Study()>& make, const StudyRunOptions& options) {
    distributed::Session session;
    study::Study s;
    std::vector<study::Job> jobs;
    session.collectively([&] {
        require_thread_count(options.threads, "--threads");
        s = make();
        jobs = study::expand(s);
        if (session.root()) std::filesystem::create_directories(s.folder);
    });
    // Every rank must have expanded the same jobs: they are handed out by index.
    session.require_same(study::to_json(s) + fmt::format("{} jobs", jobs.size()), "the study");

    std::optional<study::Manifest> manifest;
    std::vector<bool> done;
    std::vector<std::vector<int>> dependencies;
    for (const study::Job& j : jobs) dependencies.push_back(j.dependencies);
    session.collectively([&] {
        if (!session.root()) return;
        manifest.emplace(s.folder / "manifest.json", jobs, s.folder);
        done = up_to_date(jobs, *manifest);
    });
    int to_run = 0;
    if (session.root()) {
        for (const bool d : done) to_run += d ? 0 : 1;
        std::fprintf(stderr, "study %s: %zu jobs, %zu up to date, %d to run %s -> %s\n", s.origin.c_str(), jobs.size(),
                     jobs.size() - static_cast<std::size_t>(to_run), to_run,
                     session.size() > 1 ? fmt::format("on {} ranks", session.size()).c_str() : "in this process",
                     s.folder.string().c_str());
        if (options.list)
            for (std::size_t i = 0; i < jobs.size(); ++i)
                std::printf("%-12s %-11s %s\n", done[i] ? "up-to-date" : "to-run", study::to_string(jobs[i].kind),
                            jobs[i].id.c_str());
    }
    if (options.list) return;

    install_interrupt_handler();
    // Render bars on a terminal only: in a log the study's own line per job is the progress.
    const study::JobContext context{options.threads, !options.quiet && session.size() == 1 && stderr_is_terminal(),
                                    session.host()};
    const auto start = std::chrono::steady_clock::now();
    int finished = 0;
    std::vector<std::string> failures;
    bool interrupted = false;
    const auto line = [&](const char* status, const study::Job& job, const std::string& detail) {
        ++finished;
        const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double eta = elapsed * (to_run - finished) / finished;
        std::fprintf(stderr, "[%d/%d %3.0f%% ETA %s] %-11s %s%s\n", finished, to_run, 100.0 * finished / to_run,
                     format_duration(eta).c_str(), status, job.id.c_str(), detail.c_str());
    };
    distributed::JobCallbacks callbacks;
    callbacks.run = [&](int i) { return study::run_job(s, jobs[static_cast<std::size_t>(i)], context).dump(); };
    callbacks.finished = [&](int i, const std::string& text, int rank) {
        const study::Job& job = jobs[static_cast<std::size_t>(i)];
        const json report = json::parse(text);
        const std::string status = report.value("status", "failed");
        manifest->record(job, report, rank);
        const std::string where = fmt::format("rank {} ({})", rank, report.value("host", "?"));
        if (status == "failed") {
            const std::string error = report.value("error", "?");
            failures.push_back(fmt::format("{}: {}", job.id, error));
            line("FAILED", job, fmt::format(" on {}: {}", where, error));
            return;
        }
        interrupted = interrupted || status == "interrupted";
        line(status.c_str(), job,
             fmt::format("  {:.1f} s wall, {:.1f} s CPU, {}", report.value("wall_seconds", 0.0),
                         report.value("cpu_seconds", 0.0), where));
        if (report.contains("notes"))
            for (const json& note : report["notes"]) std::fprintf(stderr, "    %s\n", note.get<std::string>().c_str());
    };
    distributed::run_jobs(session, dependencies, done, callbacks);

    int status = 0;
    if (session.root()) {
        manifest->save();
        interrupted = interrupted || (interrupt_requested() && finished < to_run);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (to_run == 0)  // a finished study run again
            std::fprintf(stderr, "study %s: complete, all %zu jobs up to date (outputs in %s; manifest %s)\n",
                         s.origin.c_str(), jobs.size(), s.folder.string().c_str(), manifest->file().string().c_str());
        else
            std::fprintf(stderr, "study %s: %d of %d jobs run in %s; outputs in %s, manifest %s\n", s.origin.c_str(),
                         finished, to_run, format_duration(wall).c_str(), s.folder.string().c_str(),
                         manifest->file().string().c_str());
        if (!failures.empty()) {
            std::fprintf(stderr, "surfscatter: error: %zu job%s failed:\n", failures.size(), failures.size() > 1 ? "s" : "");
            for (const std::string& f : failures) std::fprintf(stderr, "  %s\n", f.c_str());
            status = 2;
        } else if (interrupted) {
            std::fprintf(stderr, "surfscatter: study interrupted; run the same command again to resume\n");
            status = kInterrupted;
        }
    }
    session.finish_with(status);
}

}  // namespace surfscatter::cli
