#pragma once
// Runs one job of a study (jobs.hpp) in this process.
#include <string>

#include <nlohmann/json.hpp>

#include "surfscatter/study/jobs.hpp"

namespace surfscatter::study {

struct JobContext {
    int threads = 0;         // render threads (0: all cores this process may use)
    bool progress = false;   // render progress bars on stderr
    std::string host;        // recorded in the report
};

// Runs `job`, writing its outputs under study.folder, each under a temporary name first and then renamed into
// place, so an output that exists is whole. Never throws; the report (a manifest entry without id, kind,
// parameters and rank) says what happened:
//   {"status": "done" | "failed" | "interrupted", "error": "...", "outputs": [{"path", "bytes", "fnv1a"}],
//    "inputs": [{"path", "fnv1a"}], "notes": [...], "wall_seconds", "cpu_seconds", "host"}
// A render that Ctrl-C interrupts still writes the image of the samples taken, reported "interrupted" (so the
// study renders it again when resumed).
nlohmann::json run_job(const Study& study, const Job& job, const JobContext& context);

}  // namespace surfscatter::study
