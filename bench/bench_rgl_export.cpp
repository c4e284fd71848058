// brdf export (bsdf/rgl_export.hpp) at its default resolution and tolerance (16 incidences refined where the file
// misses the model by more than 2 %, 64 x 64 samples, NDF 128, 201 wavelengths 360-1000 nm): the time of the export
// and write, and the accuracy `brdf export` prints (rgl_file_accuracy: the written file read back against the model)
// as counters: worst_pct and rms_pct (relative error of f in percent where f >= 1 % of its peak and theta_o <= 80;
// two_scale outside its jump band, bsdf/rgl_export.hpp), incidences after refinement, file_MB. Surface: photo-setup's plate (Al, KC sigma 0.15 um, L 4 um, gamma 4); the
// anisotropic case adds corr_length_v 1.5 um and a lay at 30 degrees (17 azimuths). docs/PERFORMANCE.md.
#include <benchmark/benchmark.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/rgl_export.hpp"

namespace {

namespace ss = surfscatter;

const char* kNames[] = {"ghs", "ghs_ssa", "ggx_stats", "two_scale", "ggx_stats_anisotropic"};

void BM_export(benchmark::State& state) {
    const int which = static_cast<int>(state.range(0));
    ss::bsdf::ModelOptions mo;
    const ss::bsdf::ModelKind kinds[] = {ss::bsdf::ModelKind::ghs, ss::bsdf::ModelKind::ghs_ssa,
                                         ss::bsdf::ModelKind::ggx, ss::bsdf::ModelKind::two_scale,
                                         ss::bsdf::ModelKind::ggx};
    mo.model = kinds[which];
    mo.surface.psd = ss::bsdf::PsdKind::kc;
    mo.surface.sigma = 0.15, mo.surface.corr_length = 4, mo.surface.gamma = 4;
    if (which == 4) mo.surface.corr_length_v = 1.5, mo.surface.lay_angle = 30;
    mo.material = "Al";
    const auto model = ss::bsdf::make_bsdf(mo);
    ss::bsdf::RglExportOptions o;
    o.tolerance_percent = 2;
    o.threads = 2;
    const auto path = std::filesystem::temp_directory_path() / ("bench_rgl_" + std::to_string(::getpid()) + ".bsdf");
    std::size_t incidences = 0;
    for (auto _ : state) {
        const ss::bsdf::RglData d = ss::bsdf::export_rgl(*model, o, kNames[which]);
        ss::bsdf::write_rgl(path, d);
        incidences = d.theta_i.size();
    }
    const ss::bsdf::RglAccuracy acc = ss::bsdf::rgl_file_accuracy(*model, path, o);
    state.counters["worst_pct"] = 100 * acc.worst;
    state.counters["rms_pct"] = 100 * acc.rms;
    state.counters["incidences"] = static_cast<double>(incidences);
    state.counters["file_MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
    state.counters["worst_theta_i"] = acc.theta_i_deg;
    state.counters["worst_theta_o"] = acc.theta_o_deg;
    state.counters["worst_lambda"] = acc.lambda_nm;
    state.SetLabel(kNames[which]);
    std::filesystem::remove(path);
}

}  // namespace

BENCHMARK(BM_export)->DenseRange(0, 4)->Unit(benchmark::kSecond)->MeasureProcessCPUTime()->UseRealTime()->Iterations(1);
