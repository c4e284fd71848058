// Height-map pipeline on a 1024 x 1024 map: synthesis, windowed PSD + radial average, KC fit, smoothed slope,
// .gsf write + read.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "surfscatter/surface/height_map_io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter::surface;

namespace {
const ss::KCorrelation kKc(0.05, 2.0, 3.0);
const ss::HeightMap& map_1024() {
    static const ss::HeightMap map = ss::synthesize_surface(kKc, {1024, 1024, 0.5}, 1);
    return map;
}
}  // namespace

static void BM_Synthesize1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::synthesize_surface(kKc, {1024, 1024, 0.5}, 1));
}
BENCHMARK(BM_Synthesize1024)->Unit(benchmark::kMillisecond);

static void BM_RadialPsd1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::radial_average(ss::estimate_psd(map_1024())));
}
BENCHMARK(BM_RadialPsd1024)->Unit(benchmark::kMillisecond);

static void BM_FitSurface1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::fit_surface(map_1024()));
}
BENCHMARK(BM_FitSurface1024)->Unit(benchmark::kMillisecond);

static void BM_SmoothedSlope1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::rms_slope_smoothed(map_1024(), 2.0));
}
BENCHMARK(BM_SmoothedSlope1024)->Unit(benchmark::kMillisecond);

static void BM_GsfWriteRead1024(benchmark::State& state) {
    const auto path = std::filesystem::temp_directory_path() / "surfscatter_bench_height_map.gsf";
    for (auto _ : state) {
        ss::write_gsf(map_1024(), path);
        benchmark::DoNotOptimize(ss::read_gsf(path));
    }
    std::filesystem::remove(path);
}
BENCHMARK(BM_GsfWriteRead1024)->Unit(benchmark::kMillisecond);
