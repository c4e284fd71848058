// The measured route on the real instrument files (../shared/data/realdata/heightmaps, README there; issue 33): one
// `brdf eval --psd measured` as a new user runs it, with default options, from an empty disk cache: the map read and
// prepared, its statistics, the model's lobes and the tables of the wavelength nodes around 550 nm, then three values
// (theta_i 30 deg, theta_o 0 / 30 / 60 deg in the plane of incidence, Al). Argument 0: the file (kFiles, every areal
// map surfscatter reads), 1: the route (0 ghs 2-D, 1 ghs ring, 2 ghs_ssa 2-D, 3 two_scale, 4 ggx_stats). CPU time of
// the process (the machine is shared); counter finite 1 when all three values are finite.
// BM_synthetic_brdf does the same on a synthesised KC map (L 5 um, gamma 3, 0.25 um spacing) of n x n points
// (argument 0) with sigma for g0 = (2 k sigma cos 30 deg)^2 = 10^e at 550 nm (argument 1: e), route ghs 2-D.
// Run: build/bench/bench_real_maps --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <string>

#include "empty_cache.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

constexpr std::array<const char*, 13> kFiles = {
    "metropro-1.dat", "opd-1.opd", "di-1.di",  "sur-2.sur",         "frt-2.frt", "x3p-2.x3p", "stp-1.stp",
    "mi-1.mi",        "di-2.di",   "di-5.di",  "spot_1-1000nm.ibw", "nms-1.nms", "tmd-1.tmd"};
constexpr std::array<ModelKind, 5> kRouteModels = {ModelKind::ghs, ModelKind::ghs, ModelKind::ghs_ssa,
                                                    ModelKind::two_scale, ModelKind::ggx};

void BM_real_map_brdf(benchmark::State& state) {
    const std::string file = std::string(SURFSCATTER_SHARED_DATA) + "/realdata/heightmaps/" + kFiles[std::size_t(state.range(0))];
    const int route = int(state.range(1));
    bench::EmptyCache cache("surfscatter-bench-real-maps");
    state.SetLabel(kFiles[std::size_t(state.range(0))]);
    for (auto _ : state) {
        state.PauseTiming();
        cache.renew();
        state.ResumeTiming();
        ModelOptions o;
        o.model = kRouteModels[std::size_t(route)];
        o.material = "Al";
        o.surface.psd = PsdKind::measured;
        o.surface.surface_file = file;
        o.surface.measured_spectrum = route == 1 ? MeasuredSpectrum::ring : MeasuredSpectrum::two_d;
        double sum = 0;
        try {
            load_height_map(o.surface);
            const auto bsdf = make_bsdf(o);
            const Vec3 wi = spherical_direction(30 * kDegree, 0.0);
            for (double theta_o : {0.0, 30.0, 60.0}) sum += bsdf->eval(wi, spherical_direction(theta_o * kDegree, kPi), 550.0);
        } catch (const Error& e) {
            state.SkipWithError(e.what());
        }
        benchmark::DoNotOptimize(sum);
        state.counters["finite"] = std::isfinite(sum) ? 1 : 0;
    }
}
BENCHMARK(BM_real_map_brdf)
    ->ArgsProduct({benchmark::CreateDenseRange(0, int(kFiles.size()) - 1, 1), {0, 1, 2, 3, 4}})
    ->Unit(benchmark::kSecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(1);

void BM_synthetic_brdf(benchmark::State& state) {
    const std::size_t n = std::size_t(state.range(0));
    const double g0 = std::pow(10.0, double(state.range(1)));
    const double sigma = std::sqrt(g0) / (2.0 * kTwoPi / 0.55 * std::cos(30 * kDegree));
    const auto map = std::make_shared<const heightmap::HeightMap>(
        surface::synthesize_surface(surface::KCorrelation(sigma, 5.0, 3.0), {n, n, 0.25}, 7));
    bench::EmptyCache cache("surfscatter-bench-synthetic-maps");
    for (auto _ : state) {
        state.PauseTiming();
        cache.renew();
        state.ResumeTiming();
        ModelOptions o;
        o.model = ModelKind::ghs;
        o.material = "Al";
        o.surface.psd = PsdKind::measured;
        o.surface.height_map = map;
        const auto bsdf = make_bsdf(o);
        const Vec3 wi = spherical_direction(30 * kDegree, 0.0);
        double sum = 0;
        for (double theta_o : {0.0, 30.0, 60.0}) sum += bsdf->eval(wi, spherical_direction(theta_o * kDegree, kPi), 550.0);
        benchmark::DoNotOptimize(sum);
        state.counters["finite"] = std::isfinite(sum) ? 1 : 0;
    }
}
BENCHMARK(BM_synthetic_brdf)
    ->ArgsProduct({{256, 1024}, {-3, 0, 2, 4}})
    ->Unit(benchmark::kSecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(1);

}  // namespace
