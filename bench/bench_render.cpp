// Renderer throughput: the pbrt-v4-equivalent scene of issue 5 (rough-aluminium GGX plane, 2700 K point light,
// checkerboard backdrop, depth 5, 512x512, 16 spp) and scenes/photo-setup view 1 at 512x512, 16 spp with GGX and
// with exact GHS. Counters: seconds of rendering (scene loading and BSDF table set-up excluded, reported apart),
// process CPU seconds, rays per second. One iteration each: a render is seconds long.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <filesystem>

#include "surfscatter/render/integrator.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace {

const std::filesystem::path kScenes = std::filesystem::path(__FILE__).parent_path().parent_path() / "scenes";

void render_scene(benchmark::State& state, const std::filesystem::path& scene_path,
                  const std::map<std::string, std::string>& defines) {
    for (auto _ : state) {
        const auto load_start = std::chrono::steady_clock::now();
        auto scene = surfscatter::render::load_scene(scene_path, defines);
        const double load = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
        surfscatter::render::RenderOptions options;
        options.progress = false;
        surfscatter::render::RenderStats stats;
        const std::clock_t cpu_start = std::clock();  // process CPU time, all threads
        const auto film = surfscatter::render::render(*scene, options, &stats);
        const double cpu = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
        benchmark::DoNotOptimize(film.xyz(0, 0));
        state.SetIterationTime(stats.seconds);
        state.counters["load_s"] = load;
        state.counters["render_s"] = stats.seconds;
        state.counters["rays_per_s"] = static_cast<double>(stats.rays) / stats.seconds;
        // On the shared 2-core machine wall time depends on the load; CPU seconds / 2 is the idle-machine time.
        state.counters["cpu_s"] = cpu;
        state.counters["rays_per_cpu_s"] = static_cast<double>(stats.rays) / cpu;
    }
}

void BM_PbrtEquivalentGgx(benchmark::State& state) {
    render_scene(state, kScenes / "bench" / "pbrt_equivalent.xml", {});
}

void BM_PhotoSetupView1(benchmark::State& state, const std::map<std::string, std::string>& model) {
    std::map<std::string, std::string> defines{{"view", "1"}, {"width", "512"}, {"height", "512"}, {"spp", "16"}};
    defines.insert(model.begin(), model.end());
    render_scene(state, kScenes / "photo-setup" / "scene.xml", defines);
}

}  // namespace

BENCHMARK(BM_PbrtEquivalentGgx)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_PhotoSetupView1, ggx, {{"model", "roughconductor"}})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_PhotoSetupView1, ggx_stats, {{"model", "ggx_stats"}})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
// The same plate brushed (elliptical KC: corr_length 4 um along the marks, 0.5 um across, lay at 30 deg).
BENCHMARK_CAPTURE(BM_PhotoSetupView1, ggx_stats_anisotropic,
                  {{"model", "ggx_stats"}, {"corr_length_v", "0.5"}, {"lay_angle", "30"}})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
BENCHMARK_CAPTURE(BM_PhotoSetupView1, ghs_exact, {{"model", "ghs"}})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
// The brushed plate with exact GHS (AnisotropicGhsBsdf; its azimuth tables from the disk cache after the first run).
BENCHMARK_CAPTURE(BM_PhotoSetupView1, ghs_exact_anisotropic,
                  {{"model", "ghs"}, {"corr_length_v", "0.5"}, {"lay_angle", "30"}})
    ->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);
