#include "surfscatter/distributed/render.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/core/resources.hpp"

namespace surfscatter::distributed {

namespace {

constexpr auto kReportInterval = std::chrono::milliseconds(200);
constexpr auto kCollectInterval = std::chrono::milliseconds(20);

// A rank's progress message: "p <pixel samples since the last one>", or at the end
// "d <pixel samples> <fewest samples per pixel> <most samples per pixel> <interrupted 0|1> <rays> <non-finite>".
struct Report {
    bool final = false;
    std::uint64_t advance = 0;
    int samples_per_pixel = 0;
    int max_samples_per_pixel = 0;
    bool interrupted = false;
    std::uint64_t rays = 0;
    std::uint64_t nonfinite_samples = 0;
};

std::string encode(const Report& r) {
    if (!r.final) return fmt::format("p {}", r.advance);
    return fmt::format("d {} {} {} {} {} {}", r.advance, r.samples_per_pixel, r.max_samples_per_pixel,
                       r.interrupted ? 1 : 0, r.rays, r.nonfinite_samples);
}

Report decode(const std::string& text) {
    std::istringstream in(text);
    char kind = 0;
    Report r;
    in >> kind >> r.advance;
    r.final = kind == 'd';
    if (r.final) {
        int interrupted = 0;
        in >> r.samples_per_pixel >> r.max_samples_per_pixel >> interrupted >> r.rays >> r.nonfinite_samples;
        r.interrupted = interrupted != 0;
    }
    if (!in || (kind != 'p' && kind != 'd')) fail("malformed progress message '{}'", text);
    return r;
}

}  // namespace

render::Film render(const Session& session, const render::Scene& scene, const render::RenderOptions& options,
                    render::RenderStats* stats) {
    if (session.size() == 1) return render::render(scene, options, stats);
    const auto start = std::chrono::steady_clock::now();
    const int spp = render::samples_per_pixel(scene, options);
    const std::uint64_t pixels =
        static_cast<std::uint64_t>(scene.film.output_width()) * static_cast<std::uint64_t>(scene.film.output_height());
    // Beyond the film itself (render::Film checks its own size): its state, copied once to be summed.
    session.collectively([&] {
        require_memory(double(pixels) * render::Film::kStateValues * sizeof(double),
                       fmt::format("summing a {}x{} film over ranks", scene.film.output_width(), scene.film.output_height()));
    });
    const std::uint64_t total = pixels * static_cast<std::uint64_t>(spp);
    Progress progress("render", total, session.root() && options.progress);
    render::RenderOptions part = options;
    part.part = session.rank();
    part.parts = session.size();
    part.shared_progress = &progress;

    render::RenderStats local;
    std::atomic<bool> finished{false};
    Report combined{true, 0, spp, 0, false, 0};
    std::exception_ptr relay_error;
    // The only thread that talks to MPI while the render runs (MPI_THREAD_SERIALIZED).
    std::thread relay([&] {
        try {
            if (session.root()) {
                int reported = 0;
                while (!finished.load(std::memory_order_acquire) || reported < session.size() - 1) {
                    while (auto message = session.poll(Tag::progress)) {
                        const Report r = decode(message->payload);
                        progress.advance(r.advance);
                        if (!r.final) continue;
                        ++reported;
                        combined.samples_per_pixel = std::min(combined.samples_per_pixel, r.samples_per_pixel);
                        combined.max_samples_per_pixel = std::max(combined.max_samples_per_pixel, r.max_samples_per_pixel);
                        combined.interrupted = combined.interrupted || r.interrupted;
                        combined.rays += r.rays;
                        combined.nonfinite_samples += r.nonfinite_samples;
                    }
                    std::this_thread::sleep_for(kCollectInterval);
                }
            } else {
                std::uint64_t sent = 0;
                auto next = std::chrono::steady_clock::now() + kReportInterval;
                while (!finished.load(std::memory_order_acquire)) {
                    std::this_thread::sleep_for(kCollectInterval);
                    if (std::chrono::steady_clock::now() < next) continue;
                    next += kReportInterval;
                    const std::uint64_t done = progress.done();
                    if (done > sent) session.send(0, Tag::progress, encode({false, done - sent}));
                    sent = done;
                }
                session.send(0, Tag::progress,
                             encode({true, progress.done() - sent, local.samples_per_pixel, local.max_samples_per_pixel,
                                     local.interrupted, local.rays, local.nonfinite_samples}));
            }
        } catch (...) {
            relay_error = std::current_exception();
        }
    });

    std::optional<render::Film> film;
    try {
        film.emplace(render::render(scene, part, &local));
    } catch (...) {
        session.abort(error_message(std::current_exception()));
    }
    finished.store(true, std::memory_order_release);
    relay.join();
    if (relay_error) session.abort(error_message(relay_error));
    progress.finish();

    std::vector<double> state = film->state();
    session.sum_to_root(state);
    if (session.root()) film->set_state(state);
    if (stats) {
        stats->samples_per_pixel = std::min(combined.samples_per_pixel, local.samples_per_pixel);
        stats->max_samples_per_pixel = std::max(combined.max_samples_per_pixel, local.max_samples_per_pixel);
        stats->interrupted = combined.interrupted || local.interrupted;
        stats->rays = combined.rays + local.rays;
        stats->nonfinite_samples = combined.nonfinite_samples + local.nonfinite_samples;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return std::move(*film);
}

}  // namespace surfscatter::distributed
