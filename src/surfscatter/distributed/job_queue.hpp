#pragma once
// Independent jobs over every rank with dynamic load balancing: rank 0 hands out jobs, one at a time, to whichever
// rank asks for one (a rank asks when it starts and each time it finishes a job, sending that job's report), so
// fast ranks and short jobs keep every rank busy. Rank 0 works too: a second thread on rank 0 does the handing out
// and all of its MPI traffic. Jobs are handed out in index order among those whose dependencies have finished
// (dependencies order the work; whether a dependency succeeded is for the job itself to find out). Without MPI (or
// with one rank) the same jobs run in the same order in this process.
//
// Ctrl-C (SIGINT, or the SIGTERM mpirun sends every rank): no job is handed out any more; running jobs end as their
// own code decides (renders stop within a sample) and their reports still reach rank 0.
#include <functional>
#include <string>
#include <vector>

#include "surfscatter/distributed/session.hpp"

namespace surfscatter::distributed {

struct JobCallbacks {
    // Any rank: runs job `index`, returns its report. Must not throw: a job's failure belongs in its report (an
    // exception ends the whole run through Session::abort).
    std::function<std::string(int index)> run;
    // Rank 0, always from one thread: the report of a finished job and the rank that ran it.
    std::function<void(int index, const std::string& report, int rank)> finished;
};

// Collective. `dependencies[i]` lists the jobs that job i needs (earlier jobs: indices below i); `done[i]` marks jobs that need not run (they count
// as finished). Returns when no job is left (or, after Ctrl-C, when the running ones have reported) on every rank.
void run_jobs(const Session& session, const std::vector<std::vector<int>>& dependencies, const std::vector<bool>& done,
              const JobCallbacks& callbacks);

}  // namespace surfscatter::distributed
