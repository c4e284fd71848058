#pragma once
// The one place surfscatter talks to MPI (Open MPI from Debian; mpi.h is included by session.cpp only). Nothing in
// the library depends on this module: the CLI's render, study and compare-models commands create a Session, which
// joins MPI only when an MPI launcher started the process (mpirun/mpiexec, or srun with PMI/PMIx), so a plain
// `surfscatter ...` never initialises MPI (no daemon, no network probing) and runs as one process of one rank.
//
// Errors: a step that every rank runs (loading the scene, checking options) goes through collectively(); if it
// fails on any rank, every rank leaves together (rank 0 reports, naming the ranks, the others exit quietly with
// status 2). A failure in work that ranks do on their own (rendering their tiles, running a job) ends the whole
// run at once through abort(), which names the rank and its error: a rank never waits for one that has failed.
// Waiting is done by polling with short sleeps rather than by MPI's busy-waiting calls, so a rank that waits for
// others does not take a core from the ones still working (ranks often share cores).
#include <cstdint>
#include <exception>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace surfscatter::distributed {

// True if an MPI launcher started this process (it set OMPI_COMM_WORLD_SIZE, PMIX_RANK or PMI_RANK).
bool launched_by_mpi();

// Thrown on the ranks other than 0 when a collective step failed: rank 0 reports the error, the others end with
// `status` and print nothing (the CLI's main() catches it).
class QuietExit : public std::exception {
public:
    explicit QuietExit(int status) : status_(status) {}
    int status() const { return status_; }
    const char* what() const noexcept override { return "another rank reports the error"; }

private:
    int status_;
};

// Message tags of the point-to-point traffic (progress relay, job queue).
enum class Tag : int { progress = 1, job_request = 2, job_assignment = 3 };

struct Message {
    int source = -1;
    std::string payload;
};

class Session {
public:
    Session();   // joins MPI (MPI_THREAD_SERIALIZED) if launched_by_mpi()
    ~Session();  // leaves MPI; aborts the whole run instead if an exception leaves a non-collective step
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;

    int rank() const { return rank_; }
    int size() const { return size_; }
    bool root() const { return rank_ == 0; }
    bool uses_mpi() const { return mpi_; }
    const std::string& host() const { return host_; }
    std::string describe_rank() const;  // "rank 1 of 4 (node7)"

    // Collective: runs `step` on every rank; if it throws on any rank, every rank throws (rank 0 a
    // surfscatter::Error with the message - prefixed by the ranks that had it unless all had the same - and the
    // others QuietExit(2)).
    void collectively(const std::function<void()>& step) const;
    // Collective: an error unless every rank passes the same text (e.g. its options, its film size); `what` names
    // it in the message ("rank 2's film differs from rank 0's").
    void require_same(const std::string& text, const std::string& what) const;
    // Ends every rank now: prints "surfscatter: error: rank R of N (host): message" and aborts the MPI job with
    // `status` (or exits with it when there is no MPI).
    [[noreturn]] void abort(const std::string& message, int status = 2) const;
    // Collective: every rank ends with rank 0's `status`. Returns if it is 0; else throws QuietExit(status) on every
    // rank (rank 0 has said why).
    void finish_with(int status) const;
    // Collective: a barrier that sleeps while it waits.
    void wait_for_all() const;
    // Collective: element-wise sum of every rank's `values` (same length everywhere) into rank 0's.
    void sum_to_root(std::vector<double>& values) const;
    // Collective: rank 0's `values` on every rank.
    void broadcast(std::string& value) const;

    // Point-to-point, for one thread at a time (MPI_THREAD_SERIALIZED).
    void send(int destination, Tag tag, std::string_view payload) const;
    std::optional<Message> poll(Tag tag) const;             // a waiting message from any rank, if there is one
    Message receive(int source, Tag tag) const;             // waits (sleeping) for one from `source`

private:
    bool mpi_ = false;
    int rank_ = 0;
    int size_ = 1;
    std::string host_;
    int exceptions_at_start_ = 0;
    mutable bool failed_collectively_ = false;
};

}  // namespace surfscatter::distributed
