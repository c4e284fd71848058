// fit_brdf (inverse/fit_brdf.hpp): one whole fit per model of 1,000 measured directions at each of 3 wavelengths
// (450, 550, 700 nm; the Kirchhoff BRDF of a synthesised KC map, sigma 0.12 um, L 2 um, gamma 2.5, gold, theta_i
// 30 deg, the directions whose BRDF is at least 1e-4 of the peak, the first 1,000 of them per wavelength). The time
// is the models' construction per parameter set (their tables), not the rows: docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>

#include "surfscatter/inverse/fit_brdf.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace {

namespace ss = surfscatter;

const ss::inverse::BrdfData& data() {
    static const ss::inverse::BrdfData d = [] {
        const ss::surface::KCorrelation kc(0.12, 2.0, 2.5);
        const auto map = ss::surface::synthesize_surface(kc, {512, 512, 0.25}, 7);
        const auto gold = ss::material::Conductor::from_name("Au");
        ss::inverse::BrdfData b;
        b.source = "bench";
        for (const double lambda : {450.0, 550.0, 700.0}) {
            ss::reference::KirchhoffOptions o;
            o.lambda_nm = lambda;
            o.theta_i_rad = 30 * ss::kDegree;
            o.subarea_um = 16;
            const auto r = ss::reference::kirchhoff_brdf(map, gold, o);
            const double peak = *std::max_element(r.brdf.begin(), r.brdf.end());
            std::size_t kept = 0;
            for (std::size_t j = 0; j < r.brdf.size() && kept < 1000; ++j) {
                if (!(r.brdf[j] > 1e-4 * peak)) continue;
                ++kept;
                b.wavelength_nm.push_back(lambda);
                b.theta_i_deg.push_back(30);
                b.phi_i_deg.push_back(0);
                b.theta_o_deg.push_back(std::asin(std::min(1.0, std::hypot(r.o_x[j], r.o_y[j]))) / ss::kDegree);
                b.phi_o_deg.push_back(std::atan2(r.o_y[j], r.o_x[j]) / ss::kDegree);
                b.brdf.push_back(r.brdf[j]);
            }
        }
        return b;
    }();
    return d;
}

// range(0): 0 ghs, 1 ghs_ssa, 2 ggx_stats, 3 two_scale.
void BM_FitBrdf(benchmark::State& state) {
    const ss::bsdf::ModelKind kinds[] = {ss::bsdf::ModelKind::ghs, ss::bsdf::ModelKind::ghs_ssa,
                                         ss::bsdf::ModelKind::ggx, ss::bsdf::ModelKind::two_scale};
    ss::inverse::FitOptions options;
    options.material = "Au";
    options.models = {kinds[state.range(0)]};
    const auto& d = data();
    int evaluations = 0;
    for (auto _ : state) {
        const auto result = ss::inverse::fit_brdf(d, options);
        evaluations = result.fits[0].evaluations;
        benchmark::DoNotOptimize(result.fits[0].misfit);
    }
    state.counters["rows"] = static_cast<double>(d.size());
    state.counters["models_built"] = evaluations;
    state.SetLabel(ss::bsdf::to_string(kinds[state.range(0)]));
}
BENCHMARK(BM_FitBrdf)->DenseRange(0, 3)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
