// Map preparation on a 1024 x 1024 KC map (0.5 um spacing, 512 um wide) with a waviness (a sinusoid one map long):
// row offsets and their test, the areal Gaussian filter at a short and a map-long nesting index, and the default
// lambda_c (which filters the map once or a few times), all and with 10 % of the points invalid.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>

#include "surfscatter/heightmap/gaussian_filter.hpp"
#include "surfscatter/heightmap/rows.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace hm = surfscatter::heightmap;
namespace ss = surfscatter::surface;

namespace {
const hm::HeightMap& wavy_1024(bool masked) {
    static const hm::HeightMap full = [] {
        const hm::HeightMap kc = ss::synthesize_surface(ss::KCorrelation(0.05, 2.0, 3.0), {1024, 1024, 0.5}, 1);
        std::vector<double> h = kc.heights();
        for (std::size_t iy = 0; iy < 1024; ++iy)
            for (std::size_t ix = 0; ix < 1024; ++ix)
                h[iy * 1024 + ix] += 0.2 * std::sin(2 * std::numbers::pi * (double(ix) + 0.5 * double(iy)) / 1024.0);
        return kc.with_heights(std::move(h));
    }();
    static const hm::HeightMap holes = [] {
        std::mt19937 engine(1);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        std::vector<std::uint8_t> valid(full.size(), 1);
        for (auto& v : valid) v = uniform(engine) > 0.1;
        return hm::HeightMap(1024, 1024, 0.5, 0.5, full.heights(), valid, "masked");
    }();
    return masked ? holes : full;
}
}  // namespace

static void BM_FindRowOffsets1024(benchmark::State& state) {
    const hm::HeightMap& map = wavy_1024(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(hm::find_row_offsets(map));
}
BENCHMARK(BM_FindRowOffsets1024)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Nesting index 8 um (16 pixels) and 512 um (the map's width: the padded FFT is twice the map along each axis).
static void BM_GaussianLowpass1024(benchmark::State& state) {
    const hm::HeightMap& map = wavy_1024(state.range(1));
    const double lc = double(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(hm::gaussian_lowpass(map, lc));
}
BENCHMARK(BM_GaussianLowpass1024)->Args({8, 0})->Args({512, 0})->Args({512, 1})->Unit(benchmark::kMillisecond);

static void BM_DefaultLambdaC1024(benchmark::State& state) {
    const hm::HeightMap& map = wavy_1024(state.range(0));
    std::string reason;
    for (auto _ : state) benchmark::DoNotOptimize(hm::default_lambda_c(map, &reason));
    state.SetLabel(reason.substr(0, 30));
}
BENCHMARK(BM_DefaultLambdaC1024)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
