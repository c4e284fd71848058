// Spectral core and metals: the per-path lookups the renderer and BSDFs make (CMF, Planck, n + i k, Fresnel) and
// a full 1 nm spectrum -> XYZ integration.
#include <benchmark/benchmark.h>

#include <cmath>

#include "surfscatter/material/conductor.hpp"
#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/material/refractive_index.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/cie.hpp"

namespace {

namespace ss = surfscatter::spectrum;
namespace sm = surfscatter::material;

// Wavelengths that walk over 360-830 nm so that lookups do not hit one cache line only.
double next_lambda(double& lambda) {
    lambda += 7.31;
    if (lambda > 830) lambda -= 470;
    return lambda;
}

void BM_CieXyzBar(benchmark::State& state) {
    const auto& cie = ss::cie1931();
    double lambda = 360;
    for (auto _ : state) benchmark::DoNotOptimize(cie.xyz_bar(next_lambda(lambda)));
}
BENCHMARK(BM_CieXyzBar);

void BM_BlackbodyRadiance(benchmark::State& state) {
    double lambda = 360;
    for (auto _ : state) benchmark::DoNotOptimize(ss::blackbody_radiance(next_lambda(lambda), 2700.0));
}
BENCHMARK(BM_BlackbodyRadiance);

void BM_LorentzDrudeIndex(benchmark::State& state) {
    const auto gold = sm::load_refractive_index("Au");
    double lambda = 360;
    for (auto _ : state) benchmark::DoNotOptimize(gold->at(next_lambda(lambda)));
}
BENCHMARK(BM_LorentzDrudeIndex);

void BM_TabulatedIndex(benchmark::State& state) {
    const auto gold = sm::load_refractive_index(std::string(SURFSCATTER_SHARED_DATA) + "/refractiveindex/Au_McPeak.yml");
    double lambda = 360;
    for (auto _ : state) benchmark::DoNotOptimize(gold->at(next_lambda(lambda)));
}
BENCHMARK(BM_TabulatedIndex);

void BM_FresnelConductor(benchmark::State& state) {
    double c = 0;
    for (auto _ : state) {
        c += 0.0137;
        if (c > 1.0) c -= 1.0;
        benchmark::DoNotOptimize(sm::fresnel_conductor(c, {0.36, 2.85}));
    }
}
BENCHMARK(BM_FresnelConductor);

void BM_ConductorReflectanceGold(benchmark::State& state) {
    const auto gold = sm::Conductor::from_name("Au");
    double lambda = 360, c = 0;
    for (auto _ : state) {
        c += 0.0137;
        if (c > 1.0) c -= 1.0;
        benchmark::DoNotOptimize(gold.reflectance(c, next_lambda(lambda)));
    }
}
BENCHMARK(BM_ConductorReflectanceGold);

void BM_SpectrumToXyz1nm(benchmark::State& state) {
    for (auto _ : state)
        benchmark::DoNotOptimize(ss::spectrum_to_xyz([](double l) { return ss::blackbody_radiance(l, 2700.0); }));
}
BENCHMARK(BM_SpectrumToXyz1nm);

}  // namespace
