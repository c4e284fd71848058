// Surface statistics engine: table building (FFTLog) per gamma, disk-cache load, and the lookups the BSDFs make.
// Table builds use a fresh statistics per iteration (new cache key) in a private cache directory.
#include <random>

#include <benchmark/benchmark.h>

#include "empty_cache.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"
#include "surfscatter/surface/scatter_lobe_table.hpp"
#include "surfscatter/surface/self_convolution_table.hpp"

namespace {

using namespace surfscatter::surface;

const surfscatter::bench::EmptyCache kPrivateCache("surfscatter-bench-surface-cache");

double unique_length() {
    static int counter = 0;
    return 1.0 + 1e-9 * ++counter;  // a new cache key every call
}

void BM_ScatterLobeTableBuild(benchmark::State& state) {
    const double gamma = static_cast<double>(state.range(0)) / 10.0;
    for (auto _ : state) {
        const KCorrelation kc(1.0, unique_length(), gamma);
        benchmark::DoNotOptimize(ScatterLobeTable::get(std::make_shared<KCorrelation>(kc)));
    }
}
BENCHMARK(BM_ScatterLobeTableBuild)->Arg(15)->Arg(25)->Arg(30)->Arg(40)->Iterations(3)->Unit(benchmark::kMillisecond);

void BM_ScatterLobeTableBuildGaussianAcv(benchmark::State& state) {
    for (auto _ : state) {
        const GaussianAcv g(2.27, 20.9 * unique_length());
        benchmark::DoNotOptimize(ScatterLobeTable::get(std::make_shared<GaussianAcv>(g)));
    }
}
BENCHMARK(BM_ScatterLobeTableBuildGaussianAcv)->Iterations(3)->Unit(benchmark::kMillisecond);

void BM_SelfConvolutionTableBuild(benchmark::State& state) {
    const int orders = static_cast<int>(state.range(0));
    for (auto _ : state) {
        const KCorrelation kc(1.0, unique_length(), 3.0);
        benchmark::DoNotOptimize(SelfConvolutionTable::get(kc, orders));
    }
}
BENCHMARK(BM_SelfConvolutionTableBuild)->Arg(40)->Arg(200)->Arg(1000)->Iterations(2)->Unit(benchmark::kMillisecond);

void BM_ScatterLobeTableLoadFromDisk(benchmark::State& state) {
    const KCorrelation kc(1.0, 1.0, 3.0);
    ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));  // built and written once; dropped from the process cache when released
    for (auto _ : state) benchmark::DoNotOptimize(ScatterLobeTable::get(std::make_shared<KCorrelation>(kc)));
}
BENCHMARK(BM_ScatterLobeTableLoadFromDisk)->Iterations(5)->Unit(benchmark::kMillisecond);

void BM_SelfConvolutionEval(benchmark::State& state) {
    const KCorrelation kc(1.0, 1.0, 3.0);
    const auto table = SelfConvolutionTable::get(kc, 200);
    std::mt19937 rng(1);
    std::uniform_int_distribution<int> order(1, 200);
    std::uniform_real_distribution<double> log_zeta(-3.0, 3.3);
    for (auto _ : state) benchmark::DoNotOptimize(table->eval(order(rng), std::pow(10.0, log_zeta(rng))));
}
BENCHMARK(BM_SelfConvolutionEval);

void BM_ScatterLobeEval(benchmark::State& state) {
    const KCorrelation kc(1.0, 1.0, 3.0);
    const auto table = ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> log_g(-4.0, 5.0), log_zeta(-3.0, 3.3);
    for (auto _ : state)
        benchmark::DoNotOptimize(table->eval(std::pow(10.0, log_g(rng)), std::pow(10.0, log_zeta(rng))));
}
BENCHMARK(BM_ScatterLobeEval);

void BM_ScatterLobeInverseCdf(benchmark::State& state) {
    const KCorrelation kc(1.0, 1.0, 3.0);
    const auto table = ScatterLobeTable::get(std::make_shared<KCorrelation>(kc));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> log_g(-4.0, 5.0), u(0.0, 1.0);
    for (auto _ : state) benchmark::DoNotOptimize(table->inverse_radial_cdf(std::pow(10.0, log_g(rng)), u(rng)));
}
BENCHMARK(BM_ScatterLobeInverseCdf);

void BM_VisibleDiscMass(benchmark::State& state) {
    const KCorrelation kc(0.1, 2.0, 3.0);
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> theta(0.0, 1.5), lambda(360.0, 830.0);
    for (auto _ : state) benchmark::DoNotOptimize(visible_disc_mass(kc, theta(rng), lambda(rng)));
}
BENCHMARK(BM_VisibleDiscMass)->Unit(benchmark::kMicrosecond);

void BM_KcAcv(benchmark::State& state) {
    const KCorrelation kc(1.0, 1.0, 2.5);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> r(0.0, 10.0);
    for (auto _ : state) benchmark::DoNotOptimize(kc.acv_normalized(r(rng)));
}
BENCHMARK(BM_KcAcv);

}  // namespace
