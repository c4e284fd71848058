#pragma once
// Runs a study (study/study.hpp) for `surfscatter study` and its preset `surfscatter compare-models`: over every
// MPI rank when mpirun or srun started the process (distributed/job_queue.hpp: rank 0 hands out the jobs), else in
// this process; jobs that are up to date in the manifest are skipped.
#include <functional>

#include <CLI/CLI.hpp>

#include "surfscatter/study/study.hpp"

namespace surfscatter::cli {

struct StudyRunOptions {
    int threads = 0;     // per rank (0: every core the rank may use)
    bool quiet = false;  // no render progress bars (one line per job is always printed)
    bool list = false;   // list the jobs and whether each is up to date; run nothing
};

// --threads, --quiet and --list.
void add_study_run_options(CLI::App* command, StudyRunOptions& options);

// `make` builds the study on every rank (its errors are reported once). Exit: 0; 2 (QuietExit or Error) if a job
// failed, after listing the failures; 130 if interrupted (rerun to resume).
void run_study(const std::function<study::Study()>& make, const StudyRunOptions& options);

}  // namespace surfscatter::cli
