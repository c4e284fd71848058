// The exact 1-D solver's memory bound (docs/REFERENCE.md, "Memory"): exact_1d_solve_bytes against the peak resident
// memory a solve adds, measured with getrusage in a forked child whose allocations of 64 KiB and more are fresh
// mappings (so that none reuses pages the test process already holds); and a solve beyond the available memory
// refused before it allocates, naming the options that set the node count.
#include <gtest/gtest.h>

#include <malloc.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include "reference_test_util.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

namespace sr = surfscatter::reference;
namespace sm = surfscatter::material;
using namespace reference_test;

namespace {

long max_rss_bytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss * 1024L;
}

// The peak resident bytes one solve adds, from a forked child (-1 if the child failed).
double measured_peak(const sr::Profile& profile, const sm::Conductor& conductor, const sr::Exact1dOptions& o) {
    int fds[2];
    if (pipe(fds) != 0) return -1;
    const pid_t child = fork();
    if (child == 0) {
        close(fds[0]);
        mallopt(M_MMAP_THRESHOLD, 64 * 1024);
        const long before = max_rss_bytes();
        long grown = -1;
        try {
            sr::solve_exact_1d(profile, conductor, o);
            grown = max_rss_bytes() - before;
        } catch (...) {
        }
        const bool written = write(fds[1], &grown, sizeof grown) == static_cast<ssize_t>(sizeof grown);
        _exit(written ? 0 : 1);
    }
    close(fds[1]);
    long grown = -1;
    const bool read_ok = read(fds[0], &grown, sizeof grown) == static_cast<ssize_t>(sizeof grown);
    close(fds[0]);
    int status = 0;
    waitpid(child, &status, 0);
    return read_ok && WIFEXITED(status) && WEXITSTATUS(status) == 0 ? static_cast<double>(grown) : -1.0;
}

}  // namespace

// A 400 um KC profile (sigma 0.05 um, L 2 um, gamma 3) at 550 nm, 10 points per wavelength (7,273 nodes, the
// iterative route): the bound is at least the measured peak and at most 2.5 times it, for the perfect conductor in
// s and silver in p (a few to a few tens of GMRES products: most of the Krylov basis the bound counts is never
// touched).
TEST(Exact1dMemory, BoundHoldsThePeak) {
    const surfscatter::surface::KCorrelation kc(0.05, 2.0, 3.0);
    for (const char* metal : {"perfect", "Ag"}) {
        const auto pol = std::string(metal) == "perfect" ? sr::Polarisation::s : sr::Polarisation::p;
        const auto o = solver_options(550, 30, pol, 80);
        const auto profile = sr::random_profile(kc, o, 400.0, 1);
        const auto conductor = sm::Conductor::from_name(metal);
        const double bound = sr::exact_1d_solve_bytes(profile, conductor, o);
        const double peak = measured_peak(profile, conductor, o);
        std::printf("%s: bound %.1f MB, measured peak %.1f MB (%.2fx)\n", metal, bound / 1e6, peak / 1e6, bound / peak);
        ASSERT_GT(peak, 0) << metal;
        EXPECT_GE(bound, peak) << metal;
        EXPECT_LE(bound, 2.5 * peak) << metal;
    }
}

// Nodes enough that the bound exceeds 1.5 times the memory available now (a flat profile; a few million nodes on any
// machine within kMaxExact1dNodes, which refuses the rest): refused before the solve's buffers exist, in one line
// naming the settings that fix the node count as the caller spells them (plain words by default; `surfscatter
// validity`'s --wavelengths here), for one solve and for the statistical mode's threads.
TEST(Exact1dMemory, RefusesBeyondTheAvailableMemory) {
    auto o = solver_options(550, 0, sr::Polarisation::s, 10);
    const double per_node = sr::exact_1d_solve_bytes(sr::flat_profile(o, 200.0), sm::Conductor::perfect(), o) /
                            (200.0 / 0.055);
    const double length = 1.5 * static_cast<double>(surfscatter::available_memory_bytes()) / per_node * 0.055;
    o.beam_width_um = 10;
    try {  // beyond kMaxExact1dNodes (a machine with that much memory), flat_profile refuses it in one line
        const auto profile = sr::flat_profile(o, std::min(length, 0.055 * sr::kMaxExact1dNodes * 1.1));
        sr::solve_exact_1d(profile, sm::Conductor::perfect(), o);
        ADD_FAILURE() << "a profile of " << profile.h_um.size() << " samples was solved";
    } catch (const surfscatter::Error& e) {
        const std::string what = e.what();
        std::printf("%s\n", what.c_str());
        EXPECT_EQ(what.find('\n'), std::string::npos);
        if (length < 0.055 * sr::kMaxExact1dNodes) {
            EXPECT_NE(what.find("use fewer points per wavelength (now 10), a shorter profile (now "),
                      std::string::npos) << what;
        }
    }
    // Two threads of a statistical run whose one solve fits but whose two do not, with validity's option names.
    const double half = 0.6 * static_cast<double>(surfscatter::available_memory_bytes()) / per_node * 0.055;
    if (half < 0.055 * sr::kMaxExact1dNodes) {
        o.option_names = {.length = "--length-um", .wavelength = "--wavelengths",
                          .points_per_wavelength = "--points-per-wavelength", .threads = "--threads"};
        const auto fits = sr::flat_profile(o, half);
        EXPECT_NO_THROW(sr::require_exact_1d_memory(fits, sm::Conductor::perfect(), o, 1));
        try {
            sr::require_exact_1d_memory(fits, sm::Conductor::perfect(), o, 2);
            ADD_FAILURE() << "two solves of " << fits.h_um.size() << " nodes passed";
        } catch (const surfscatter::Error& e) {
            const std::string what = e.what();
            std::printf("%s\n", what.c_str());
            EXPECT_NE(what.find("use fewer --points-per-wavelength (now 10), a shorter --length-um (now "), std::string::npos)
                << what;
            EXPECT_NE(what.find(" or a longer --wavelengths (now 550 nm), or fewer --threads (now 2 at once)"),
                      std::string::npos) << what;
        }
    }
}
