// Height-map pipeline on a 1024 x 1024 map: synthesis, windowed PSD + radial average, KC fit, smoothed slope,
// file reading (.gsf native, .gwy through Gwyddion, Gwyddion text export), and, with 10 % invalid points (5 % at
// random, a band of 5 % of the rows), form removal, the masked PSD, the ACV measures and the KC fit.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "surfscatter/heightmap/gwyddion_file.hpp"
#include "surfscatter/surface/height_map_acv.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/elliptical_fit.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter::surface;
namespace hm = surfscatter::heightmap;
namespace fs = std::filesystem;

namespace {
const ss::KCorrelation kKc(0.05, 2.0, 3.0);
const hm::HeightMap& map_1024() {
    static const hm::HeightMap map = ss::synthesize_surface(kKc, {1024, 1024, 0.5}, 1);
    return map;
}
// The same surface with 10 % of its points invalid.
const hm::HeightMap& masked_1024() {
    static const hm::HeightMap map = [] {
        const hm::HeightMap& full = map_1024();
        std::mt19937 engine(1);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        std::vector<std::uint8_t> valid(full.size(), 1);
        for (std::size_t i = 0; i < valid.size(); ++i)
            if (uniform(engine) < 0.05 || (i / 1024 >= 500 && i / 1024 < 551)) valid[i] = 0;
        return hm::HeightMap(1024, 1024, 0.5, 0.5, full.heights(), valid, "masked");
    }();
    return map;
}
fs::path scratch(const std::string& name) { return fs::temp_directory_path() / ("surfscatter_bench_" + name); }
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

// The elliptical KC fit alone (part of fit_surface), on the periodogram and isotropic fit it starts from.
static void BM_EllipticalFit1024(benchmark::State& state) {
    const ss::SurfaceFit fit = ss::fit_surface(map_1024());
    for (auto _ : state) benchmark::DoNotOptimize(ss::fit_elliptical_kc(fit.spectrum, fit.kc));
}
BENCHMARK(BM_EllipticalFit1024)->Unit(benchmark::kMillisecond);

static void BM_SmoothedSlope1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::rms_slope_smoothed(map_1024(), 2.0));
}
BENCHMARK(BM_SmoothedSlope1024)->Unit(benchmark::kMillisecond);

static void BM_GsfWriteRead1024(benchmark::State& state) {
    const auto path = scratch("height_map.gsf");
    for (auto _ : state) {
        hm::write_gsf(map_1024(), path);
        benchmark::DoNotOptimize(hm::read_gsf(path));
    }
    fs::remove(path);
}
BENCHMARK(BM_GsfWriteRead1024)->Unit(benchmark::kMillisecond);

// read_height_map as a user calls it: format detection (Gwyddion's detector included) and the reader.
static void BM_ReadGsf1024(benchmark::State& state) {
    const auto path = scratch("read.gsf");
    hm::write_gsf(masked_1024(), path);
    for (auto _ : state) benchmark::DoNotOptimize(hm::read_height_map(path, std::nullopt));
    fs::remove(path);
}
BENCHMARK(BM_ReadGsf1024)->Unit(benchmark::kMillisecond);

static void BM_ReadGwyThroughGwyddion1024(benchmark::State& state) {
    const auto path = scratch("read.gwy");
    hm::gwyddion_write_gwy(masked_1024(), path);
    for (auto _ : state) benchmark::DoNotOptimize(hm::read_height_map(path, std::nullopt));
    fs::remove(path);
}
BENCHMARK(BM_ReadGwyThroughGwyddion1024)->Unit(benchmark::kMillisecond);

static void BM_ReadGwyddionTextExport1024(benchmark::State& state) {
    const auto path = scratch("read.txt");
    {
        std::ofstream out(path);
        out << "# Channel: Height\n# Width: 512.0 \xc2\xb5m\n# Height: 512.0 \xc2\xb5m\n# Value units: m\n";
        const hm::HeightMap& map = masked_1024();
        for (std::size_t iy = 0; iy < map.ny(); ++iy)
            for (std::size_t ix = 0; ix < map.nx(); ++ix)
                out << (map.valid(ix, iy) ? fmt::format("{:.6g}", 1e-6 * map(ix, iy)) : "nan")
                    << (ix + 1 == map.nx() ? '\n' : '\t');
    }
    for (auto _ : state) benchmark::DoNotOptimize(hm::read_height_map(path, std::nullopt));
    fs::remove(path);
}
BENCHMARK(BM_ReadGwyddionTextExport1024)->Unit(benchmark::kMillisecond);

static void BM_FormRemoval1024(benchmark::State& state) {
    const auto form = static_cast<hm::Form>(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(hm::remove_form(masked_1024(), form));
    state.SetLabel(hm::to_string(form) + ", 10 % invalid");
}
BENCHMARK(BM_FormRemoval1024)
    ->Arg(static_cast<int>(hm::Form::plane))
    ->Arg(static_cast<int>(hm::Form::poly2))
    ->Arg(static_cast<int>(hm::Form::poly4))
    ->Unit(benchmark::kMillisecond);

static void BM_MaskedRadialPsd1024(benchmark::State& state) {
    for (auto _ : state) benchmark::DoNotOptimize(ss::radial_average(ss::estimate_psd(masked_1024())));
}
BENCHMARK(BM_MaskedRadialPsd1024)->Unit(benchmark::kMillisecond);

static void BM_MaskedFitSurface1024(benchmark::State& state) {
    ss::KcFitOptions options;
    options.form = hm::Form::poly2;
    for (auto _ : state) benchmark::DoNotOptimize(ss::fit_surface(masked_1024(), options));
}
BENCHMARK(BM_MaskedFitSurface1024)->Unit(benchmark::kMillisecond);

static void BM_AcvMeasures1024(benchmark::State& state) {
    const hm::HeightMap flat = hm::remove_form(state.range(0) ? masked_1024() : map_1024(), hm::Form::plane);
    for (auto _ : state) benchmark::DoNotOptimize(ss::acv_measures(flat));
    state.SetLabel(state.range(0) ? "10 % invalid" : "all valid");
}
BENCHMARK(BM_AcvMeasures1024)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// Everything `surfscatter surface info` computes after reading: form, moments, slope, ACV measures.
static void BM_SurfaceInfo1024(benchmark::State& state) {
    for (auto _ : state) {
        const hm::HeightMap flat = hm::remove_form(masked_1024(), hm::Form::plane);
        benchmark::DoNotOptimize(hm::height_moments(flat));
        benchmark::DoNotOptimize(ss::rms_slope(flat, hm::Form::none));
        benchmark::DoNotOptimize(ss::acv_measures(flat));
    }
}
BENCHMARK(BM_SurfaceInfo1024)->Unit(benchmark::kMillisecond);
