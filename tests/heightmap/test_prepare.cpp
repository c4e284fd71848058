// The preparation of a map on synthesised data of known statistics (issue 33, "Done when"): a KC surface plus row
// offsets, a waviness of two oblique long-period sinusoids, a tilt and white noise. After row alignment (auto), form
// removal (plane) and the default L-filter, the prepared map's rms is the KC surface's within the band the filter
// keeps (a quadrature of its PSD times the filter's transmission) to within its stated standard error, the waviness
// rms is the sinusoids' (times their transmission) and the KC surface's long periods, and the offsets are recovered.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <numbers>
#include <random>
#include <vector>

#include "height_test_util.hpp"
#include "row_profile.hpp"
#include "surfscatter/heightmap/form.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/heightmap/gaussian_filter.hpp"
#include "surfscatter/heightmap/prepare.hpp"
#include "surfscatter/heightmap/rows.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::heightmap {
using surface::KCorrelation;
using surface::synthesize_surface;
namespace {

constexpr double kPi = std::numbers::pi;
const double kAlpha = std::sqrt(std::log(2.0) / kPi);

double rms_of(const HeightMap& map) {
    double s = 0, s2 = 0;
    for (std::size_t i = 0; i < map.size(); ++i)
        if (map.valid(i)) s += map.heights()[i], s2 += map.heights()[i] * map.heights()[i];
    const double n = double(map.valid_count());
    return std::sqrt(s2 / n - (s / n) * (s / n));
}

struct Wave { double amplitude; int mx, my; };  // A cos(2 pi (mx x / W + my y / H)): whole periods along each row

TEST(Prepare, SynthesisedMapRecoversItsStatistics) {
    const std::size_t n = 512;
    const double spacing = 1.0, width = double(n) * spacing;
    const double sigma = 0.05, noise = 0.005, offsets_rms = 0.01;
    const KCorrelation kc(sigma, 2.0, 3.0);
    const HeightMap surface = synthesize_surface(kc, {n, n, spacing}, 77);
    const std::vector<Wave> waves = {{0.2, 1, 1}, {0.1, 2, -1}};
    std::mt19937_64 rng(13);
    std::normal_distribution<double> normal;
    std::vector<double> offsets(n);
    for (double& o : offsets) o = offsets_rms * normal(rng);
    std::vector<double> h = surface.heights();
    for (double& v : h) v += noise * normal(rng);
    const HeightMap clean = surface.with_heights(h);  // what row alignment cannot tell from offsets: its row means
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix) {
            const double x = double(ix) * spacing, y = double(iy) * spacing;
            double v = offsets[iy] + 0.0005 * x + 0.00025 * y;
            for (const Wave& w : waves) v += w.amplitude * std::cos(2 * kPi * (w.mx * x + w.my * y) / width);
            h[iy * n + ix] += v;
        }
    const HeightMap measured = surface.with_heights(std::move(h));

    // The one preparation every consumer uses, with its defaults (outliers kept, rows auto, plane, lambda_c auto).
    const PreparedMap prepared = prepare(measured, Preparation{});
    const RowOffsets& found = prepared.rows;
    ASSERT_TRUE(found.detected && prepared.rows_aligned) << found.reason;
    const std::string& reason = prepared.lambda_c_reason;
    const double lc = prepared.applied.lambda_c_um.value_or(0.0);
    ASSERT_GT(lc, 0.0) << reason;
    ASSERT_TRUE(prepared.waviness.has_value());
    EXPECT_FALSE(is_periodic(prepared.map)) << "filtered: the statistics take the Hann window";
    const double stated = sigma_relative_error(prepared.map);

    // Truth. The KC surface's variance kept and removed by the filter: its PSD times the power transmissions over
    // the lattice's band (midpoint rule in zeta up to Nyquist), the sinusoids' exactly, the noise's kept whole (the
    // filter removes a fraction of about pi (spacing / (2 alpha lc))^2 < 1e-4 of it).
    const double nyquist = kPi / spacing, dzeta = nyquist / 20000;
    double kept = 0, removed = 0, total = 0;
    for (double zeta = 0.5 * dzeta; zeta < nyquist; zeta += dzeta) {
        const double low = std::exp(-kPi * std::pow(kAlpha * lc * zeta / (2 * kPi), 2));
        const double mass = kc.psd(zeta) * 2 * kPi * zeta * dzeta;
        kept += mass * (1 - low) * (1 - low), removed += mass * low * low, total += mass;
    }
    double waves_kept = 0, waves_removed = 0;
    for (const Wave& w : waves) {
        const double period = width / std::hypot(w.mx, w.my);
        const double low = std::exp(-kPi * std::pow(kAlpha * lc / period, 2));
        waves_kept += 0.5 * w.amplitude * w.amplitude * (1 - low) * (1 - low);
        waves_removed += 0.5 * w.amplitude * w.amplitude * low * low;
    }
    const double rms_truth = std::sqrt(kept + waves_kept + noise * noise);
    const double waviness_truth = std::sqrt(removed + waves_removed);
    const double rms = rms_of(prepared.map), waviness = rms_of(*prepared.waviness);
    EXPECT_NEAR(prepared.waviness_rms_um, waviness, 1e-12);
    RecordProperty("lambda_c_um", std::to_string(lc));
    RecordProperty("prepared_rms_um", std::to_string(rms));
    RecordProperty("truth_rms_um", std::to_string(rms_truth));
    RecordProperty("waviness_rms_um", std::to_string(waviness));
    RecordProperty("truth_waviness_rms_um", std::to_string(waviness_truth));
    RecordProperty("stated_error", std::to_string(stated));
    EXPECT_LE(stated, kLambdaCSigmaError) << reason;
    EXPECT_NEAR(rms / rms_truth, 1.0, 2 * stated) << reason << "; rms " << rms << " truth " << rms_truth;
    EXPECT_NEAR(waviness / waviness_truth, 1.0, 0.05) << waviness << " truth " << waviness_truth;
    // The offsets, less their cubic in y (form), within 1.5 x the surface's own row-mean profile (sigma / sqrt(the
    // independent points a row holds), which the median of differences takes with them).
    const std::vector<double> expected = test::minus_cubic(offsets), profile = test::row_means(clean);
    double err = 0;
    for (std::size_t iy = 0; iy < n; ++iy) err += std::pow(found.white_um[iy] - expected[iy], 2);
    RecordProperty("offsets_error_um", std::to_string(std::sqrt(err / double(n))));
    RecordProperty("row_profile_um", std::to_string(test::rms(profile)));
    EXPECT_LT(std::sqrt(err / double(n)), 1.5 * test::rms(profile)) << found.reason;
    EXPECT_NEAR(found.white_rms_um, test::rms(expected), 1.5 * test::rms(profile));
}

// A synthesised periodic map stays periodic through the outliers and the form (judged as read), not through a filter.
TEST(Prepare, PeriodicityIsJudgedAsRead) {
    const HeightMap map = synthesize_surface(KCorrelation(0.05, 2.0, 3.0), {256, 256, 0.25}, 3);
    ASSERT_TRUE(is_periodic(map));
    Preparation poly2;
    poly2.form = Form::poly2;
    poly2.lambda_c_um = 0.0;
    EXPECT_FALSE(is_periodic(remove_form(map, Form::poly2))) << "the form fitted to it breaks the wrap-around";
    EXPECT_TRUE(is_periodic(prepare(map, poly2).map));
    Preparation filtered = poly2;
    filtered.lambda_c_um = 20.0;
    EXPECT_FALSE(is_periodic(prepare(map, filtered).map));
}

TEST(Prepare, NestingIndicesAreParsedOrNamed) {
    EXPECT_FALSE(parse_lambda_c("auto", "--lambda-c").has_value());
    EXPECT_EQ(parse_lambda_c("none", "--lambda-c"), 0.0);
    EXPECT_EQ(parse_lambda_c("25", "--lambda-c"), 25.0);
    EXPECT_EQ(parse_lambda_s("2.5", "--lambda-s"), 2.5);
    EXPECT_EQ(parse_lambda_s("none", "--lambda-s"), 0.0);
    for (const char* bad : {"", "-1", "0", "nan", "inf", "25um", "auto"})
        EXPECT_EQ(test::error_of([&] { parse_lambda_s(bad, "--lambda-s"); }).find("--lambda-s must be a nesting index"), 0u)
            << bad;
    const HeightMap map = synthesize_surface(KCorrelation(0.05, 2.0, 3.0), {64, 64, 0.25}, 3);
    Preparation crossed;
    crossed.lambda_s_um = 4.0;
    crossed.lambda_c_um = 2.0;
    EXPECT_NE(test::error_of([&] { prepare(map, crossed); }).find("must be longer than lambda_s"), std::string::npos);
}

// ---------------------------------------------------------------- real instrument files

// The default preparation's numerics on the real maps of ../shared/data/realdata/heightmaps (.tmd and .nms are
// tested in test_height_formats.cpp; .opdx and .hfm are profiles): row alignment (auto), plane,
// the default lambda_c; where it filters, the filtered map's sigma is estimable (standard error <= 10 %).
TEST(Prepare, RealFilesGetAnEstimableSigma) {
    const std::vector<std::string> files = {"metropro-1.dat", "opd-1.opd", "di-1.di", "di-2.di", "di-5.di",
                                            "frt-2.frt", "mi-1.mi", "sur-2.sur", "x3p-2.x3p", "stp-1.stp",
                                            "spot_1-1000nm.ibw", "mnt-1.mnt"};
    for (const std::string& name : files) {
        const auto path = std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "heightmaps" / name;
        const HeightMap map = read_height_map(path, std::nullopt);
        RowOffsets rows;
        const HeightMap flat = remove_form(align_rows(map, RowAlignment::automatic, rows), Form::plane);
        std::string reason;
        const double lc = default_lambda_c(flat, &reason);
        const double before = sigma_relative_error(flat);
        double after = before, waviness = 0, rms = rms_of(flat);
        if (lc > 0) {
            const Filtered f = l_filter(flat, lc);
            after = sigma_relative_error(f.kept), waviness = rms_of(f.removed), rms = rms_of(f.kept);
            EXPECT_LE(after, kLambdaCSigmaError) << name << ": " << reason;
            // The longest such: the next nesting index of the 1-2-5 series leaves sigma's error above 10 %.
            const double mantissa = lc / std::pow(10.0, std::floor(std::log10(lc) + 1e-9));
            const double next = lc * (std::abs(mantissa - 2.0) < 1e-6 ? 2.5 : 2.0);
            if (next <= std::max(map.width(), map.height())) {
                EXPECT_GT(sigma_relative_error(l_filter(flat, next).kept), kLambdaCSigmaError) << name << " " << next;
            }
        } else {
            EXPECT_TRUE(before <= kLambdaCSigmaError || reason.find("no nesting index") != std::string::npos)
                << name << ": " << reason;
        }
        std::printf("%-18s %4zu x %-4zu %9.4g x %-9.4g um  rows %-8s R %-9.3g W %-9.3g lambda_c %-7g um  rms %-10.4g "
                    "waviness %-10.4g um  sigma error %5.1f %% -> %5.1f %%\n",
                    name.c_str(), map.nx(), map.ny(), map.width(), map.height(),
                    rows.detected ? "aligned" : (rows.lay ? "lay" : "-"), rows.ratio, rows.white_ratio, lc, rms, waviness, 100 * before, 100 * after);
    }
}

}  // namespace
}  // namespace surfscatter::heightmap
