// The 2-D measured route (`--psd measured`, measured_spectrum 2d; surface/spectrum_lobes_2d.hpp, bsdf/map_ghs.hpp) of a
// 1024^2 map of a KC surface (sigma for g0 = 10 at 550 nm and 30 deg, L = 1 um, gamma 3) at 0.05 um: the lobes
// (SpectrumLobes2d) from the map's periodogram, one wavelength node's sigma_rel / K tables (disk cache pointed at an
// empty folder), and eval at 550 nm against the isotropic exact GHS of the ring average (the same map) and of the KC
// statistics, random direction pairs about theta_i = 30 deg.
// Run: build/bench/bench_map_ghs --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "empty_cache.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/map_ghs.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

constexpr double kLambda = 550.0;
const double kSigma = std::sqrt(10.0) / (2.0 * kTwoPi / (kLambda * 1e-3) * std::cos(30 * kDegree));

const std::shared_ptr<const surface::MapStatistics>& map_statistics() {
    static const auto stats = std::make_shared<const surface::MapStatistics>(
        surface::synthesize_surface(surface::KCorrelation(kSigma, 1.0, 3.0), {1024, 1024, 0.05}, 1),
        heightmap::Form::plane);
    return stats;
}

ModelOptions options(int route) {
    ModelOptions o;
    o.model = ModelKind::ghs;
    if (route == 2) {  // the KC statistics themselves
        o.surface.psd = PsdKind::kc;
        o.surface.sigma = kSigma;
        o.surface.corr_length = 1.0;
        o.surface.gamma = 3.0;
        return o;
    }
    o.surface.psd = PsdKind::measured;
    o.surface.measured_psd = map_statistics();
    o.surface.measured_spectrum = route == 0 ? MeasuredSpectrum::two_d : MeasuredSpectrum::ring;
    return o;
}

void BM_map2d_lobes(benchmark::State& state) {
    const auto& stats = map_statistics();
    for (auto _ : state) benchmark::DoNotOptimize(map_lobes(stats->spectrum()));
}
BENCHMARK(BM_map2d_lobes)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(3);

// One wavelength node's tables from nothing: the first eval at a node's own wavelength reads two (its interval's).
void BM_map2d_tables(benchmark::State& state) {
    const auto lobes = map_lobes(map_statistics()->spectrum());
    bench::EmptyCache cache("surfscatter-bench-map2d");
    for (auto _ : state) {
        state.PauseTiming();
        cache.renew();
        GhsSettings settings;
        const MapGhsBsdf bsdf(lobes, std::nullopt, material::Conductor::from_name("perfect"), settings);
        state.ResumeTiming();
        benchmark::DoNotOptimize(bsdf.eval(Vec3(0.5, 0, std::sqrt(0.75)), Vec3(-0.5, 0.1, 0.86), kLambda));
    }
}
BENCHMARK(BM_map2d_tables)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(2);

// eval: 0 the 2-D route, 1 the ring average of the same map, 2 the KC statistics (isotropic exact GHS).
void BM_map2d_eval(benchmark::State& state) {
    const auto bsdf = make_bsdf(options(int(state.range(0))));
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<std::pair<Vec3, Vec3>> pairs;
    for (int n = 0; n < 4096; ++n) {
        const double pi_i = kTwoPi * u(rng), t_o = 0.5 * kPi * std::sqrt(u(rng)), p_o = kTwoPi * u(rng);
        pairs.push_back({spherical_direction(30 * kDegree, pi_i), spherical_direction(t_o, p_o)});
    }
    for (const auto& [wi, wo] : pairs) bsdf->eval(wi, wo, kLambda);  // tables built before timing
    std::size_t i = 0;
    for (auto _ : state) {
        const auto& [wi, wo] = pairs[i++ & 4095];
        benchmark::DoNotOptimize(bsdf->eval(wi, wo, kLambda));
    }
}
BENCHMARK(BM_map2d_eval)->Arg(0)->Arg(1)->Arg(2);

}  // namespace
