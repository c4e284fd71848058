// The measured-PSD route (psd measured: the height map's own ring spectrum, MapStatistics) against
// the KC-fit route (psd file) and the truth, on synthesized maps written as .gsf files: for a KC surface both routes
// agree with the true lobe within the periodogram's statistical error; for surfaces no KC can represent (a Gaussian
// ACV, which the KC fit rejects, and the sum of two KC surfaces of different lengths, which it fits badly) the measured
// route follows the true lobe and the KC fit does not. Lobes are compared by their relative L1
// distance over the hemisphere at theta_i = 30 deg (lobe_distance.hpp), where the per-bin scatter of the binned
// periodogram (~10 %) averages out. The map is read once per model: GGX alpha_from measured with psd measured uses
// the map's own slopes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "lobe_distance.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;
namespace fs = std::filesystem;

namespace {

constexpr double kLambda = 550.0;

// A 1024 x 1024 map at 0.08 um spacing (82 um, 82 correlation lengths; Nyquist 39 rad/um > 2 k = 23 rad/um, so the
// lobe needs no extrapolation beyond the data) written to a scratch .gsf.
fs::path synthesized(const surface::RadialStatistics& truth, const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / "surfscatter_test_measured";
    fs::create_directories(dir);
    const fs::path path = dir / (name + ".gsf");
    heightmap::write_gsf(surface::synthesize_surface(truth, {1024, 1024, 0.08}, 11), path);
    return path;
}

ModelOptions from_map(const fs::path& path, PsdKind psd) {
    ModelOptions o;
    o.surface.psd = psd;
    o.surface.surface_file = path.string();
    o.surface.measured_spectrum = MeasuredSpectrum::ring;  // this file tests the ring route (test_map_ghs.cpp: 2d)
    return o;
}

}  // namespace

TEST(Measured, KcMapBothRoutesFollowTheTruth) {
    const surface::KCorrelation truth(0.1, 1.0, 3.0);
    const fs::path path = synthesized(truth, "kc");
    const auto exact = make_bsdf(test::kc_options(ModelKind::ghs, 0.1, 1.0, 3.0));
    std::vector<std::string> notes;
    const auto measured = make_bsdf(from_map(path, PsdKind::measured), &notes);
    const auto fitted = make_bsdf(from_map(path, PsdKind::file));
    const double d_measured = test::lobe_distance(*measured, *exact, kLambda);
    const double d_fitted = test::lobe_distance(*fitted, *exact, kLambda);
    std::printf("KC map: lobe distance to the truth, measured PSD %.3f, KC fit %.3f\n", d_measured, d_fitted);
    EXPECT_LT(d_measured, 0.05);
    EXPECT_LT(d_fitted, 0.05);
    EXPECT_LT(test::lobe_distance(*measured, *fitted, kLambda), 0.05);
    // What the estimate rests on is reported: the band, sigma against the map's rms, the samples of the lowest rings
    // and the wavelengths whose lobes reach beyond the band.
    // The map's preparation first, then the measured PSD's note.
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("prepared: outliers keep"), std::string::npos) << notes[0];
    for (const char* part : {"band zeta", "rolled off", "against the map's rms", "independent samples",
                             "longer than a third of the map", "beyond the band"})
        EXPECT_NE(notes[1].find(part), std::string::npos) << part << ": " << notes[1];
}

TEST(Measured, GaussianAcvMapOnlyTheMeasuredRouteFollowsTheTruth) {
    const surface::GaussianAcv truth(0.1, 1.0);
    const fs::path path = synthesized(truth, "gaussian");
    ModelOptions t;
    t.surface.psd = PsdKind::gaussian;
    t.surface.sigma = 0.1;
    t.surface.corr_length = 1.0;
    const auto exact = make_bsdf(t);
    const auto measured = make_bsdf(from_map(path, PsdKind::measured));
    const double d_measured = test::lobe_distance(*measured, *exact, kLambda);
    std::printf("Gaussian-ACV map: lobe distance to the truth, measured PSD %.3f (no KC fits it)\n", d_measured);
    EXPECT_LT(d_measured, 0.05);
    EXPECT_THROW(make_bsdf(from_map(path, PsdKind::file)), Error);  // "a PSD falling faster than any power law"
}

namespace {

// Two KC components of different lengths (sigma 0.08 um, L 3 um, gamma 4 and sigma 0.06 um, L 0.3 um, gamma 3): a PSD
// with two knees.
class TwoKc final : public surface::RadialStatistics {
public:
    double sigma_h() const override { return std::hypot(a_.sigma_h(), b_.sigma_h()); }
    double psd_unit(double z) const override { return (a_.psd(z) + b_.psd(z)) / (sigma_h() * sigma_h()); }
    double acv_normalized(double r) const override { return (a_.acv(r) + b_.acv(r)) / (sigma_h() * sigma_h()); }
    double radial_cdf(double z) const override {
        return (a_.sigma_h() * a_.sigma_h() * a_.radial_cdf(z) + b_.sigma_h() * b_.sigma_h() * b_.radial_cdf(z)) /
               (sigma_h() * sigma_h());
    }
    double correlation_length() const override { return b_.correlation_length(); }
    std::string cache_key() const override { return "test-two-kc(" + a_.cache_key() + "," + b_.cache_key() + ")"; }

private:
    surface::KCorrelation a_{0.08, 3.0, 4.0}, b_{0.06, 0.3, 3.0};
};

}  // namespace

TEST(Measured, TwoLengthMapOnlyTheMeasuredRouteFollowsTheTruth) {
    const auto truth = std::make_shared<TwoKc>();
    const fs::path path = synthesized(*truth, "two_kc");
    const GhsBsdf exact(truth, std::make_shared<ExactScatterCore>(truth), material::Conductor::from_name("perfect"), {});
    const auto measured = make_bsdf(from_map(path, PsdKind::measured));
    const auto fitted = make_bsdf(from_map(path, PsdKind::file));
    const double d_measured = test::lobe_distance(*measured, exact, kLambda);
    const double d_fitted = test::lobe_distance(*fitted, exact, kLambda);
    std::printf("two-length map: lobe distance to the truth, measured PSD %.3f, KC fit %.3f\n", d_measured, d_fitted);
    EXPECT_LT(d_measured, 0.05);
    EXPECT_GT(d_fitted, 3.0 * d_measured);
}

TEST(Measured, GgxKeepsTheMapsSlopeAndRefitNeedsKc) {
    const fs::path path = synthesized(surface::KCorrelation(0.1, 1.0, 3.0), "kc_slope");
    ModelOptions o = from_map(path, PsdKind::measured);
    o.model = ModelKind::ggx;
    o.alpha_from = AlphaFrom::measured;
    const auto ggx = make_bsdf(o);
    const double alpha = surface::rms_slope(heightmap::read_height_map(path, std::nullopt));
    const Vec3 wi = spherical_direction(0.4, 0.0), wo = spherical_direction(0.5, kPi);
    o.alpha_from = AlphaFrom::none;
    o.alpha = alpha;
    EXPECT_DOUBLE_EQ(ggx->eval(wi, wo, kLambda), make_bsdf(o)->eval(wi, wo, kLambda));
    ModelOptions refit = from_map(path, PsdKind::measured);
    refit.method = GhsMethod::refit;
    EXPECT_THROW(make_bsdf(refit), Error);
    ModelOptions link = from_map(path, PsdKind::measured);
    link.model = ModelKind::ggx;
    link.alpha_from = AlphaFrom::kc_link;
    EXPECT_THROW(make_bsdf(link), Error);
}
