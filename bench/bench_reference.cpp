// The exact 1-D solver: one solve of a KC profile (sigma 0.05 um, L 2 um, gamma 3) at 550 nm, 10 points per
// wavelength, against profile length, for the perfect conductor (s, p) and silver (s, p), dense LU against the
// iterative route (and at 100 um on the supplemental rough surface, KC sigma 0.15 um, L 4 um, gamma 4); and the statistical mode's
// realizations on 1 and 2 threads, and the variance reduction of its control variate. The dense solve alone at 1,820 unknowns: Eigen's PartialPivLU against LAPACK's
// zgetrf/zgetrs (reference/dense_solve.hpp), like with like in one run. The Kirchhoff BRDF of a KC map (sigma 0.1 or 0.5 um, L 2 um, gamma 4, 0.1 um
// pixels) of 512^2 and 1024^2 points at 550 nm, theta_i 30 deg, gold, 16 sub-areas, on 1 and 2 threads. CPU and wall time are reported separately (docs/PERFORMANCE.md).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/dense_solve.hpp"
#include "surfscatter/reference/exact_1d.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace {

namespace sr = surfscatter::reference;

sr::Exact1dOptions bench_options(sr::Polarisation pol) {
    sr::Exact1dOptions o;
    o.lambda_nm = 550;
    o.theta_i_rad = 30 * surfscatter::kDegree;
    o.polarisation = pol;
    o.points_per_wavelength = 10;
    return o;
}

// range(0): profile length in um (beam width a fifth of it); range(1): 0 perfect s, 1 perfect p, 2 Ag s, 3 Ag p;
// range(2): 0 dense LU, 1 iterative (docs/REFERENCE.md, "Solve"); range(3): 0 the KC profile above, 1 the
// supplemental rough surface (KC sigma 0.15 um, L 4 um, gamma 4: k sigma 1.7 at 550 nm).
void BM_Exact1dSolve(benchmark::State& state) {
    const double length = static_cast<double>(state.range(0));
    const int mode = static_cast<int>(state.range(1));
    auto o = bench_options(mode % 2 == 0 ? sr::Polarisation::s : sr::Polarisation::p);
    o.beam_width_um = length / 5;
    o.solver = state.range(2) == 0 ? sr::Exact1dSolver::dense : sr::Exact1dSolver::iterative;
    const surfscatter::surface::KCorrelation kc = state.range(3) == 0 ? surfscatter::surface::KCorrelation(0.05, 2.0, 3.0)
                                                                      : surfscatter::surface::KCorrelation(0.15, 4.0, 4.0);
    const auto profile = sr::random_profile(kc, o, length, 1);
    const auto metal = mode < 2 ? surfscatter::material::Conductor::perfect()
                                : surfscatter::material::Conductor::from_name("Ag");
    for (auto _ : state) benchmark::DoNotOptimize(sr::solve_exact_1d(profile, metal, o));
    state.counters["unknowns"] = static_cast<double>(profile.h_um.size());
}
BENCHMARK(BM_Exact1dSolve)
    ->ArgsProduct({{25, 50, 100}, {0, 1, 2, 3}, {0, 1}, {0}})
    ->ArgsProduct({{100}, {0, 1, 2, 3}, {0, 1}, {1}})
    ->Iterations(2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// range(0): 0 Eigen's PartialPivLU, 1 LAPACK (solve_dense), on a 1,820-unknown system (a 100 um profile's).
void BM_DenseSolve(benchmark::State& state) {
    const Eigen::Index n = 1820;
    Eigen::MatrixXcd a = Eigen::MatrixXcd::Random(n, n);
    a.diagonal().array() += 2.0;
    const Eigen::VectorXcd b = Eigen::VectorXcd::Random(n);
    for (auto _ : state) {
        if (state.range(0) == 0)
            benchmark::DoNotOptimize(Eigen::PartialPivLU<Eigen::MatrixXcd>(a).solve(b).eval());
        else
            benchmark::DoNotOptimize(sr::solve_dense(a, b, "the benchmark system"));
    }
}
BENCHMARK(BM_DenseSolve)->Arg(0)->Arg(1)->Iterations(2)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

// Four realizations of 50 um profiles (perfect conductor, s) on range(0) threads.
void BM_Exact1dStatistics(benchmark::State& state) {
    auto o = bench_options(sr::Polarisation::s);
    o.beam_width_um = 10;
    const surfscatter::surface::KCorrelation kc(0.05, 2.0, 3.0);
    sr::StatisticalOptions st;
    st.length_um = 50;
    st.realizations = 4;
    st.seed = 1;
    st.threads = static_cast<int>(state.range(0));
    for (auto _ : state)
        benchmark::DoNotOptimize(sr::solve_exact_1d_statistics(kc, surfscatter::material::Conductor::perfect(), o, st));
}
BENCHMARK(BM_Exact1dStatistics)->Arg(1)->Arg(2)->Iterations(1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

// The control variate at docs/VALIDITY.md's settings (40 um profiles, 8 um beam, 48 realizations, Ag, 550 nm): the
// supplemental's rough (range(0) = 1: KC sigma 0.15 um, L 4 um, gamma 4) and smooth (0: sigma 0.02 um, L 2 um,
// gamma 3) surfaces at theta_i = range(1) deg, s (range(2) = 0) or p. Counters: the median over the directions
// holding >= 1 % of the lobe's peak of the variance reduction (plain / controlled standard error, squared) and of
// the controlled and plain relative standard errors.
void BM_Exact1dVarianceReduction(benchmark::State& state) {
    auto o = bench_options(state.range(2) == 0 ? sr::Polarisation::s : sr::Polarisation::p);
    o.theta_i_rad = static_cast<double>(state.range(1)) * surfscatter::kDegree;
    o.beam_width_um = 8;
    const surfscatter::surface::KCorrelation kc = state.range(0) == 1 ? surfscatter::surface::KCorrelation(0.15, 4.0, 4.0)
                                                                      : surfscatter::surface::KCorrelation(0.02, 2.0, 3.0);
    sr::StatisticalOptions st;
    st.length_um = 40;
    st.realizations = 48;
    st.seed = 1;
    st.threads = 1;
    sr::StatisticalResult r;
    for (auto _ : state) r = sr::solve_exact_1d_statistics(kc, surfscatter::material::Conductor::from_name("Ag"), o, st);
    const double peak = *std::max_element(r.incoherent_plain.begin(), r.incoherent_plain.end());
    std::vector<double> reduction, controlled, plain;
    for (std::size_t j = 0; j < r.theta_o_rad.size(); ++j) {
        if (r.incoherent_plain[j] < 0.01 * peak) continue;
        reduction.push_back(std::pow(r.incoherent_plain_stderr[j] / r.incoherent_stderr[j], 2));
        controlled.push_back(r.incoherent_stderr[j] / r.incoherent[j]);
        plain.push_back(r.incoherent_plain_stderr[j] / r.incoherent_plain[j]);
    }
    const auto median = [](std::vector<double> v) {
        std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
        return v[v.size() / 2];
    };
    state.counters["variance_reduction"] = median(reduction);
    state.counters["rel_stderr_controlled"] = median(controlled);
    state.counters["rel_stderr_plain"] = median(plain);
}
BENCHMARK(BM_Exact1dVarianceReduction)
    ->ArgsProduct({{0, 1}, {0, 30, 60}, {0, 1}})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

// range(0): map side in pixels; range(1): threads; range(2): sigma in nm.
void BM_KirchhoffMap(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const surfscatter::surface::KCorrelation kc(static_cast<double>(state.range(2)) * 1e-3, 2.0, 4.0);
    const auto map = surfscatter::surface::synthesize_surface(kc, {n, n, 0.1}, 1);
    sr::KirchhoffOptions o;
    o.lambda_nm = 550;
    o.theta_i_rad = 30 * surfscatter::kDegree;
    o.subarea_um = 0.25 * map.width();
    o.threads = static_cast<int>(state.range(1));
    const auto gold = surfscatter::material::Conductor::from_name("Au");
    std::size_t ffts = 0, directions = 0;
    for (auto _ : state) {
        const auto r = sr::kirchhoff_brdf(map, gold, o);
        ffts = r.fft_count;
        directions = r.brdf.size();
        benchmark::DoNotOptimize(r.albedo);
    }
    state.counters["ffts_per_subarea"] = static_cast<double>(ffts);
    state.counters["directions"] = static_cast<double>(directions);
}
BENCHMARK(BM_KirchhoffMap)
    ->ArgsProduct({{512, 1024}, {1, 2}, {100, 500}})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
