// eval / sample / pdf of every scattering model at g0 = 0.1, 10, 1000 (theta_i = 30 deg, 550 nm, KC gamma = 3,
// L = 1 um, perfect conductor), and eval with varying incidence and wavelength; ghs_measured is exact GHS on the
// measured route's ring average (`--psd measured --measured-spectrum ring`, map_statistics.hpp) of a 1024^2 map of that KC surface at 0.05 um, and
// BM_measured_tables builds its tables from nothing (the disk cache pointed at an empty folder). The per-wavelength tables (sigma_rel,
// K) are built before timing. aniso_ghs_exact / aniso_ghs_ssa: the same surfaces made elliptical (LV = 0.4 LU, lay angle
// 30 deg; AnisotropicGhsBsdf), aniso_two_scale two_scale's (N 50). BM_eval_packet: the renderer's four-wavelength
// call (f and the reverse pdf).
// Run: build/bench/bench_bsdf --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "empty_cache.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

constexpr double kLambda = 550.0;
constexpr double kThetaI = 30.0 * kDegree;

ModelOptions options_for(int model, double g) {
    ModelOptions o;
    o.surface.psd = PsdKind::kc;
    o.surface.gamma = 3.0;
    o.surface.corr_length = 1.0;
    o.surface.sigma = std::sqrt(g) / (2.0 * kTwoPi / (kLambda * 1e-3));
    switch (model) {
        case 0: o.model = ModelKind::ghs; break;
        case 1: o.model = ModelKind::ghs; o.method = GhsMethod::refit; break;
        case 2: o.model = ModelKind::ghs_ssa; break;
        case 3: o.model = ModelKind::ggx; o.alpha_from = AlphaFrom::smoothed; o.smoothing = 0.1; break;
        case 4: o.model = ModelKind::two_scale; o.cutoff_wavelengths = 50; break;
        case 6:  // elliptical: LV = 0.4 LU, lay angle 30 deg (AnisotropicGhsBsdf)
        case 7:
            o.model = model == 6 ? ModelKind::ghs : ModelKind::ghs_ssa;
            o.surface.corr_length_v = 0.4;
            o.surface.lay_angle = 30.0;
            break;
        case 9:  // model 4 on elliptical statistics (LV = 0.4 LU, lay 30 deg): anisotropic macro NDF and micro GHS
            o.model = ModelKind::two_scale;
            o.cutoff_wavelengths = 50;
            o.surface.corr_length_v = 0.4;
            o.surface.lay_angle = 30.0;
            break;
        case 8:  // model 3 on elliptical statistics (LV = 0.3 LU, lay 30 deg): the anisotropic GGX path
            o.model = ModelKind::ggx;
            o.alpha_from = AlphaFrom::smoothed;
            o.smoothing = 0.1;
            o.surface.corr_length_v = 0.3;
            o.surface.lay_angle = 30;
            break;
        default: {
            o.model = ModelKind::ghs;
            o.surface.psd = PsdKind::measured;
            o.surface.measured_spectrum = MeasuredSpectrum::ring;  // the ring route (bench_map_ghs: the 2-D one)
            o.surface.surface_file = "kc-1024.gsf";  // named for reports; the map is given
            o.surface.height_map = std::make_shared<const heightmap::HeightMap>(surface::synthesize_surface(
                surface::KCorrelation(o.surface.sigma, 1.0, 3.0), {1024, 1024, 0.05}, 1));
            break;
        }
    }
    return o;
}

const Bsdf& model(int m, double g) {
    static std::map<std::pair<int, double>, std::unique_ptr<Bsdf>> cache;
    auto& b = cache[{m, g}];
    if (!b) {
        b = make_bsdf(options_for(m, g));
        b->eval(spherical_direction(kThetaI, 0), Vec3(0, 0, 1), kLambda);  // build the tables
    }
    return *b;
}

// Outgoing directions from the model's own sampler: the queries a renderer makes.
std::vector<Vec3> directions(const Bsdf& b, const Vec3& wi) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Vec3> out;
    while (out.size() < 1024) {
        const auto s = b.sample(wi, kLambda, 0.999999 * u(rng) + 1e-6, Vec2(u(rng), u(rng)));
        if (s && !s->delta) out.push_back(s->wo);
        if (!s || s->delta) out.push_back(spherical_direction(std::acos(u(rng)), kTwoPi * u(rng)));
    }
    return out;
}

const char* kNames[] = {"ghs_exact", "ghs_refit", "ghs_ssa", "ggx", "two_scale", "ghs_measured", "aniso_ghs_exact",
                        "aniso_ghs_ssa", "ggx_anisotropic", "aniso_two_scale"};

void BM_eval(benchmark::State& state) {
    const Bsdf& b = model(int(state.range(0)), std::pow(10.0, double(state.range(1)) - 1));
    const Vec3 wi = spherical_direction(kThetaI, 0);
    const auto wos = directions(b, wi);
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(b.eval(wi, wos[i++ & 1023], kLambda));
    state.SetLabel(kNames[state.range(0)]);
}

void BM_pdf(benchmark::State& state) {
    const Bsdf& b = model(int(state.range(0)), std::pow(10.0, double(state.range(1)) - 1));
    const Vec3 wi = spherical_direction(kThetaI, 0);
    const auto wos = directions(b, wi);
    std::size_t i = 0;
    for (auto _ : state) benchmark::DoNotOptimize(b.pdf(wi, wos[i++ & 1023], kLambda));
    state.SetLabel(kNames[state.range(0)]);
}

void BM_sample(benchmark::State& state) {
    const Bsdf& b = model(int(state.range(0)), std::pow(10.0, double(state.range(1)) - 1));
    const Vec3 wi = spherical_direction(kThetaI, 0);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    for (auto _ : state) benchmark::DoNotOptimize(b.sample(wi, kLambda, u(rng), Vec2(u(rng), u(rng))));
    state.SetLabel(kNames[state.range(0)]);
}

// eval with a new incidence direction and wavelength on every call (64 incidences x 4 wavelengths, 16 outgoing
// directions each from the model's sampler): what a path tracer asks, with no (theta_i, lambda) reuse to benefit from.
void BM_eval_varying(benchmark::State& state) {
    const Bsdf& b = model(int(state.range(0)), std::pow(10.0, double(state.range(1)) - 1));
    struct Query {
        Vec3 wi, wo;
        double lambda;
    };
    std::vector<Query> queries;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 64; ++i)
        for (double lambda : {450.0, 520.0, 590.0, 660.0}) {
            const Vec3 wi = spherical_direction(std::acos(0.05 + 0.95 * u(rng)), kTwoPi * u(rng));
            for (int j = 0; j < 16; ++j) {
                const auto s = b.sample(wi, lambda, u(rng), Vec2(u(rng), u(rng)));
                queries.push_back({wi, s && !s->delta ? s->wo : spherical_direction(std::acos(u(rng)), kTwoPi * u(rng)),
                                   lambda});
            }
        }
    std::shuffle(queries.begin(), queries.end(), rng);
    std::size_t i = 0;
    for (auto _ : state) {
        const Query& q = queries[i++ & 4095];
        benchmark::DoNotOptimize(b.eval(q.wi, q.wo, q.lambda));
    }
    state.SetLabel(kNames[state.range(0)]);
}

// The renderer's call: f and the reverse density for the four wavelengths of a path (Bsdf::eval_packet), the
// directions of BM_eval, wavelengths 450 / 520 / 590 / 660 nm (their tables and proposals built before timing).
// Time per packet; the counter is CPU time per wavelength.
// BM_eval_packet_loop: the interface's default, eval and pdf one wavelength at a time, for comparison.
template <bool kOwn>
void BM_eval_packet(benchmark::State& state) {
    const Bsdf& b = model(int(state.range(0)), std::pow(10.0, double(state.range(1)) - 1));
    const auto packet = [&](const Vec3& wi, const Vec3& wo, const WavelengthValues& lambda, WavelengthValues* pdf) {
        return kOwn ? b.eval_packet(wi, wo, lambda, pdf) : b.Bsdf::eval_packet(wi, wo, lambda, pdf);
    };
    const Vec3 wi = spherical_direction(kThetaI, 0);
    const auto wos = directions(b, wi);
    const WavelengthValues lambdas{450.0, 520.0, 590.0, 660.0};
    WavelengthValues pdf{};
    for (const Vec3& wo : wos) packet(wi, wo, lambdas, &pdf);  // builds these wavelengths' tables
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(packet(wi, wos[i++ & 1023], lambdas, &pdf));
        benchmark::DoNotOptimize(pdf);
    }
    state.counters["per_wavelength"] = benchmark::Counter(double(state.iterations()) * double(lambdas.size()),
                                                          benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(kNames[state.range(0)]);
}

// Arguments: model index, log10(g) + 1 (0 -> g = 0.1, 2 -> 10, 4 -> 1000).
void models_and_g(benchmark::internal::Benchmark* b) {
    for (int m = 0; m < 10; ++m)
        for (int lg : {0, 2, 4}) b->Args({m, lg});
}

// The measured route's tables of a 1024^2 map from nothing: statistics, lobe tables, the per-wavelength sigma_rel
// and K (one incidence and wavelength), as the first eval of a process with an empty disk cache builds them.
void BM_measured_tables(benchmark::State& state) {
    ModelOptions o = options_for(5, 10.0);
    bench::EmptyCache cache("surfscatter-bench-measured");
    int run = 0;
    for (auto _ : state) {
        state.PauseTiming();
        cache.renew();
        // A new map each run: the tables are also shared in memory by their statistics.
        o.surface.height_map = std::make_shared<const heightmap::HeightMap>(surface::synthesize_surface(
            surface::KCorrelation(o.surface.sigma, 1.0, 3.0), {1024, 1024, 0.05}, 100 + ++run));
        state.ResumeTiming();
        const auto b = make_bsdf(o);
        benchmark::DoNotOptimize(b->eval(spherical_direction(kThetaI, 0), Vec3(0, 0, 1), kLambda));
    }
}

// The exact-GHS sigma_rel / K tables on their first build, for photo-setup's plate (Al, KC sigma 0.15 um, LU 4 um,
// gamma 4): range(0) = 0 isotropic (GhsBsdf, 64 integrals a wavelength node), 1 brushed (LV 0.5 um, lay 30 deg:
// AnisotropicGhsBsdf, 64 x 9; bench_render's ghs_exact_anisotropic), the disk cache pointed at an empty folder and the
// core's lobe tables built before timing. Each iteration evaluates at a wavelength between two wavelength nodes no
// earlier iteration touched, so it builds exactly two nodes' tables; the counter per_node is time per node.
void BM_ghs_tables(benchmark::State& state) {
    const bench::EmptyCache cache("surfscatter-bench-ghs-tables");
    ModelOptions o;
    o.material = "Al";
    o.surface.psd = PsdKind::kc;
    o.surface.sigma = 0.15;
    o.surface.corr_length = 4.0;
    o.surface.gamma = 4.0;
    if (state.range(0) == 1) {
        o.surface.corr_length_v = 0.5;
        o.surface.lay_angle = 30.0;
    }
    const auto b = make_bsdf(o);
    const Vec3 wi = spherical_direction(kThetaI, 0);
    benchmark::DoNotOptimize(b->eval(wi, Vec3(0, 0, 1), 380.0));  // the core's tables and the nodes about 380 nm
    int pair = 0;
    for (auto _ : state) {
        // Nodes are 2 % apart: the middle of the interval 2 pair + 4 intervals above 380 nm.
        const double lambda = 380.0 * std::exp(0.02 * (2.0 * pair++ + 4.5));
        benchmark::DoNotOptimize(b->eval(wi, Vec3(0, 0, 1), lambda));
    }
    state.counters["per_node"] = benchmark::Counter(2.0 * double(state.iterations()),
                                                    benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.SetLabel(state.range(0) == 1 ? "brushed" : "isotropic");
}

}  // namespace

BENCHMARK(BM_eval)->Apply(models_and_g);
BENCHMARK(BM_pdf)->Apply(models_and_g);
BENCHMARK(BM_sample)->Apply(models_and_g);
BENCHMARK(BM_measured_tables)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(3);
BENCHMARK(BM_ghs_tables)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->Iterations(4);
BENCHMARK(BM_eval_varying)->Args({0, 2})->Args({3, 2})->Args({6, 2});
void packet_models(benchmark::internal::Benchmark* b) {
    for (int m : {0, 3, 6, 8})
        for (int lg : {0, 2, 4}) b->Args({m, lg});
}
BENCHMARK(BM_eval_packet<true>)->Name("BM_eval_packet")->Apply(packet_models);
BENCHMARK(BM_eval_packet<false>)->Name("BM_eval_packet_loop")->Apply(packet_models);

// The 1-D forms (bsdf/profile_lobes.hpp): one lobe on exact-1d's 1801-angle grid, its K included, for a KC profile
// (sigma 0.05 um, gamma 3) of correlation length range(1) / 2 um at 550 nm, theta_i 30 deg, perfect conductor, s;
// range(0): 0 ghs, 1 ghs_ssa, 2 kirchhoff.
namespace {
void BM_profile_lobe(benchmark::State& state) {
    namespace sb = surfscatter::bsdf;
    sb::ProfileModelOptions options;
    options.model = static_cast<sb::ProfileModel>(state.range(0));
    const surfscatter::surface::KCorrelation kc(0.05, 0.5 * static_cast<double>(state.range(1)), 3.0);
    const auto grid = sb::uniform_theta_grid(1800);
    for (auto _ : state)
        benchmark::DoNotOptimize(sb::profile_lobe(kc, surfscatter::material::Conductor::perfect(), 550,
                                                  30 * surfscatter::kDegree, sb::ProfilePolarisation::s, options, grid));
}
}  // namespace
BENCHMARK(BM_profile_lobe)
    ->ArgsProduct({{0, 1, 2}, {1, 4, 16}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(3);

// The 1-D two_scale lobe (its micro GHS with K and the macro GGX's energy) of the supplemental's rough surface (KC
// sigma 0.15 um, L 4 um, gamma 4), Ag, 550 nm, p, at theta_i range(0) deg, on every range(1)-th direction of exact-1d's
// 1801-angle grid: what docs/VALIDITY.md's cases spend per model and incidence.
namespace {
void BM_two_scale_profile_lobe(benchmark::State& state) {
    namespace sb = surfscatter::bsdf;
    const surfscatter::surface::KCorrelation kc(0.15, 4.0, 4.0);
    const auto ag = surfscatter::material::Conductor::from_name("Ag");
    std::vector<double> grid;
    const auto all = sb::uniform_theta_grid(1800);
    for (std::size_t j = 0; j < all.size(); j += static_cast<std::size_t>(state.range(1))) grid.push_back(all[j]);
    for (auto _ : state)
        benchmark::DoNotOptimize(sb::two_scale_profile_lobe(kc, ag, 550, static_cast<double>(state.range(0)) *
                                                                             surfscatter::kDegree,
                                                            sb::ProfilePolarisation::p, grid));
}
}  // namespace
BENCHMARK(BM_two_scale_profile_lobe)
    ->ArgsProduct({{0, 60}, {1, 16}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Iterations(1);
