#include "surfscatter/distributed/session.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <thread>

#include <mpi.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/paths.hpp"

namespace surfscatter::distributed {

namespace {

// Polling interval while waiting for other ranks: short against any job, long against MPI's progress loop.
constexpr auto kPollInterval = std::chrono::milliseconds(2);

void check(int status, const char* call) {
    if (status != MPI_SUCCESS) {
        char text[MPI_MAX_ERROR_STRING];
        int length = 0;
        MPI_Error_string(status, text, &length);
        fail("{} failed: {}", call, std::string(text, static_cast<std::size_t>(length)));
    }
}

// Waits for a non-blocking request with sleeps between tests (MPI_Wait would spin on a core).
void wait_quietly(MPI_Request& request) {
    for (;;) {
        int done = 0;
        check(MPI_Test(&request, &done, MPI_STATUS_IGNORE), "MPI_Test");
        if (done) return;
        std::this_thread::sleep_for(kPollInterval);
    }
}

}  // namespace

bool launched_by_mpi() {
    for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
        if (std::getenv(variable)) return true;
    return false;
}

Session::Session() : host_(host_name()), exceptions_at_start_(std::uncaught_exceptions()) {
    if (!launched_by_mpi()) return;
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised) fail("MPI is already initialised in this process (one Session at a time)");
    int provided = 0;
    check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
    mpi_ = true;
    // Errors are reported through return codes and end the run through abort(), never by MPI killing us silently.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    if (provided < MPI_THREAD_SERIALIZED)
        abort(fmt::format("this MPI library offers thread level {} (MPI_THREAD_SERIALIZED = {} is needed)", provided,
                          MPI_THREAD_SERIALIZED));
}

Session::~Session() {
    if (!mpi_) return;
    if (std::uncaught_exceptions() > exceptions_at_start_ && !failed_collectively_) {
        // Other ranks may be waiting for this one in a collective step: end them too rather than hang.
        std::fprintf(stderr, "surfscatter: error: %s: failed outside a collective step; ending every rank\n",
                     describe_rank().c_str());
        MPI_Abort(MPI_COMM_WORLD, 2);
    }
    MPI_Finalize();
}

std::string Session::describe_rank() const { return fmt::format("rank {} of {} ({})", rank_, size_, host_); }

void Session::abort(const std::string& message, int status) const {
    if (mpi_ && size_ > 1) std::fprintf(stderr, "surfscatter: error: %s: %s\n", describe_rank().c_str(), message.c_str());
    else std::fprintf(stderr, "surfscatter: error: %s\n", message.c_str());
    std::fflush(stderr);
    if (mpi_) MPI_Abort(MPI_COMM_WORLD, status);
    std::_Exit(status);
}

void Session::wait_for_all() const {
    if (!mpi_) return;
    MPI_Request request;
    check(MPI_Ibarrier(MPI_COMM_WORLD, &request), "MPI_Ibarrier");
    wait_quietly(request);
}

void Session::collectively(const std::function<void()>& step) const {
    std::string error;
    try {
        step();
    } catch (...) {
        error = error_message(std::current_exception());
        if (!mpi_) throw;
    }
    if (!mpi_) return;
    wait_for_all();
    // Every rank's message (empty if it succeeded) gathered on rank 0.
    const int length = static_cast<int>(error.size());
    std::vector<int> lengths(static_cast<std::size_t>(size_));
    check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    std::vector<int> offsets(lengths.size(), 0);
    for (std::size_t r = 1; r < lengths.size(); ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    std::string all(root() ? static_cast<std::size_t>(offsets.back() + lengths.back()) : 0, '\0');
    check(MPI_Gatherv(error.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                      MPI_COMM_WORLD),
          "MPI_Gatherv");
    int failed = error.empty() ? 0 : 1;
    check(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
    if (!failed) return;
    failed_collectively_ = true;
    if (!root()) throw QuietExit(2);
    // One line: the message itself if every rank that failed had the same one, else each with its ranks.
    std::map<std::string, std::vector<int>> ranks_by_message;
    for (int r = 0; r < size_; ++r)
        if (lengths[static_cast<std::size_t>(r)] > 0)
            ranks_by_message[all.substr(static_cast<std::size_t>(offsets[static_cast<std::size_t>(r)]),
                                        static_cast<std::size_t>(lengths[static_cast<std::size_t>(r)]))]
                .push_back(r);
    if (ranks_by_message.size() == 1 && ranks_by_message.begin()->second.size() == static_cast<std::size_t>(size_))
        throw Error(ranks_by_message.begin()->first);
    std::string text;
    for (const auto& [message, ranks] : ranks_by_message) {
        if (!text.empty()) text += "; ";
        text += ranks.size() == 1 ? fmt::format("rank {}", ranks[0]) : fmt::format("ranks {}", fmt::join(ranks, ","));
        text += ": " + message;
    }
    throw Error(text);
}

void Session::finish_with(int status) const {
    std::string text = std::to_string(status);
    broadcast(text);
    const int agreed = std::stoi(text);
    if (agreed == 0) return;
    failed_collectively_ = true;
    throw QuietExit(agreed);
}

void Session::require_same(const std::string& text, const std::string& what) const {
    if (!mpi_) return;
    std::string reference = text;
    broadcast(reference);
    collectively([&] {
        if (reference != text) fail("{} is not the same as on rank 0: '{}' here, '{}' on rank 0", what, text, reference);
    });
}

void Session::broadcast(std::string& value) const {
    if (!mpi_) return;
    wait_for_all();
    std::uint64_t length = value.size();
    check(MPI_Bcast(&length, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Bcast");
    value.resize(length);
    check(MPI_Bcast(value.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD), "MPI_Bcast");
}

void Session::sum_to_root(std::vector<double>& values) const {
    if (!mpi_) return;
    wait_for_all();
    // MPI counts are ints: large images go in chunks.
    constexpr std::size_t kChunk = std::size_t{1} << 26;
    for (std::size_t begin = 0; begin < values.size(); begin += kChunk) {
        const int count = static_cast<int>(std::min(kChunk, values.size() - begin));
        double* data = values.data() + begin;
        check(MPI_Reduce(root() ? MPI_IN_PLACE : data, root() ? data : nullptr, count, MPI_DOUBLE, MPI_SUM, 0,
                         MPI_COMM_WORLD),
              "MPI_Reduce");
    }
}

void Session::send(int destination, Tag tag, std::string_view payload) const {
    if (payload.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) fail("message too long");
    check(MPI_Send(payload.data(), static_cast<int>(payload.size()), MPI_CHAR, destination, static_cast<int>(tag),
                   MPI_COMM_WORLD),
          "MPI_Send");
}

namespace {
Message receive_probed(const MPI_Status& status) {
    int count = 0;
    check(MPI_Get_count(&status, MPI_CHAR, &count), "MPI_Get_count");
    Message message;
    message.source = status.MPI_SOURCE;
    message.payload.resize(static_cast<std::size_t>(count));
    check(MPI_Recv(message.payload.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "MPI_Recv");
    return message;
}
}  // namespace

std::optional<Message> Session::poll(Tag tag) const {
    int waiting = 0;
    MPI_Status status;
    check(MPI_Iprobe(MPI_ANY_SOURCE, static_cast<int>(tag), MPI_COMM_WORLD, &waiting, &status), "MPI_Iprobe");
    if (!waiting) return std::nullopt;
    return receive_probed(status);
}

Message Session::receive(int source, Tag tag) const {
    for (;;) {
        int waiting = 0;
        MPI_Status status;
        check(MPI_Iprobe(source, static_cast<int>(tag), MPI_COMM_WORLD, &waiting, &status), "MPI_Iprobe");
        if (waiting) return receive_probed(status);
        std::this_thread::sleep_for(kPollInterval);
    }
}

}  // namespace surfscatter::distributed
