#pragma once
// manifest.json in the study folder: one entry per job of the study, in job order -
//   {"id", "kind", "parameters", "needs": [ids of the jobs it waited for],
//    "status": "done" | "failed" | "interrupted", "error", "outputs": [{"path", "bytes", "fnv1a"}],
//    "inputs": [{"path", "fnv1a"}], "wall_seconds", "cpu_seconds", "rank", "host", "finished"}
// rewritten (temporary file + rename) after every job, so a killed study keeps the record of every job it finished.
// A job is up to date - skipped when the study runs again - if its entry is "done" with the same parameters and
// every output (and every input it read) still has the recorded size and FNV-1a 64 hash.
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "surfscatter/study/jobs.hpp"

namespace surfscatter::study {

struct Fingerprint {
    std::uintmax_t bytes = 0;
    std::string fnv1a;  // 16 hex digits
};
std::optional<Fingerprint> fingerprint(const std::filesystem::path& file);  // nullopt unless a regular file

class Manifest {
public:
    // Reads `file` if it exists (an unreadable one is an error naming it); entries of jobs that are not in `jobs`
    // any more are dropped.
    Manifest(std::filesystem::path file, const std::vector<Job>& jobs, const std::filesystem::path& folder);

    bool up_to_date(const Job& job) const;
    // Replaces the job's entry with `report` (run_job's) plus its id, kind, parameters and the rank that ran it,
    // and rewrites the file.
    void record(const Job& job, nlohmann::json report, int rank);
    void save() const;

    const std::filesystem::path& file() const { return file_; }

private:
    std::filesystem::path file_;
    std::filesystem::path folder_;
    const std::vector<Job>& jobs_;
    std::map<std::string, nlohmann::json> entries_;
};

}  // namespace surfscatter::study
