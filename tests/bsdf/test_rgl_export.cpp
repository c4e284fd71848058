// brdf export (bsdf/rgl_export.hpp) against the models themselves: each exported file is written, read back and
// evaluated as the format prescribes (RglMeasuredBsdf, the reading of Mitsuba 3's and pbrt-v4's `measured`), and
// compared with the model's own eval wherever f >= 1 % of its peak, at the file's incidence nodes and between them;
// the directional albedo of the read-back lobe against the model's continuous albedo. Fast settings (few
// wavelengths, coarse grids); the default resolution is measured in bench/ and docs/MODELS.md.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <string>

#include <fmt/format.h>

#include "model_fixtures.hpp"
#include "surfscatter/bsdf/albedo.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/rgl_export.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

struct Errors {
    double worst = 0;  // max relative error where f >= 1 % of the peak
    double albedo = 0; // relative error of the directional albedo
    std::string where;
};

// The file holds f cos(theta_o); a reader divides by cos(theta_o), which magnifies its interpolation error toward
// the horizon: directions beyond this are left out of the pointwise comparison (the albedo still covers them).
constexpr double kGrazingDeg = 80;

// Exports `model`, reads the file back and measures the error at incidence theta_deg (azimuth phi_deg).
Errors measure(const Bsdf& model, const RglExportOptions& o, const std::vector<double>& thetas_deg, double phi_deg,
               double lambda) {
    const auto dir = std::filesystem::temp_directory_path() / ("rgl_export_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    write_rgl(dir / "model.bsdf", export_rgl(model, o, "test"));
    const RglMeasuredBsdf back(read_rgl(dir / "model.bsdf"));
    std::filesystem::remove_all(dir);
    Errors e;
    for (double theta_deg : thetas_deg) {
        const Vec3 wi = spherical_direction(theta_deg * kDegree, phi_deg * kDegree);
        std::vector<std::pair<Vec3, double>> grid;
        double peak = 0;
        for (int a = 0; a < 90; ++a)
            for (int b = 0; b < 180; ++b) {
                const Vec3 wo = spherical_direction((a + 0.5) * kDegree, (b + 0.5) * 2 * kDegree);
                const double f = model.eval(wi, wo, lambda);
                grid.push_back({wo, f});
                peak = std::max(peak, f);
            }
        for (const auto& [wo, f] : grid)
            if (f >= 0.01 * peak && wo.z >= std::cos(kGrazingDeg * kDegree) &&
                std::abs(back.eval(wi, wo, lambda) / f - 1) > e.worst) {
                e.worst = std::abs(back.eval(wi, wo, lambda) / f - 1);
                e.where = fmt::format("theta_i {} theta_o {:.1f} phi_o {:.1f}", theta_deg, std::acos(wo.z) / kDegree,
                                      std::atan2(wo.y, wo.x) / kDegree);
            }
        const auto a_model = directional_albedo(model, theta_deg * kDegree, lambda, phi_deg * kDegree);
        const auto a_back = directional_albedo(back, theta_deg * kDegree, lambda, phi_deg * kDegree);
        e.albedo = std::max(e.albedo, std::abs(a_back.total() / (a_model.total() - a_model.specular) - 1));
    }
    return e;
}

RglExportOptions fast(int theta_count) {
    RglExportOptions o;
    o.theta_i_count = theta_count;
    o.theta_i_max_deg = 80;
    o.sample_resolution = 48;
    o.ndf_resolution = 96;
    o.lambda_min_nm = 500, o.lambda_max_nm = 600, o.lambda_step_nm = 50;
    o.threads = 2;
    return o;
}

}  // namespace

// Measured with these settings (worst relative error where f >= 1 % of the peak and theta_o <= 80 deg; albedo), with
// the warp adapted to each incidence's lobe: ghs 0.9 % at nodes, 2.0 % between (theta_i 45, next to the specular
// direction), albedo 0.04 / 0.9 %; ghs_ssa 1.7 / 1.9 %, albedo 0.08 / 0.13 %; ggx_stats 1.6 / 1.5 % (theta_o 79.5),
// albedo 0.2 %; two_scale 11 / 36 % within half a degree of the specular direction (its macro spike, narrower than
// the sample grid and changing shape between incidence nodes), albedo 0.5 / 2.9 %. Before (the standard VNDF warp of
// the NDF alone): ghs 6.2 / 2.0 %, ghs_ssa 50 / 14 %, ggx_stats 8.6 / 9.5 %, two_scale 205 / 188 % (albedo 30 %).
// Each bound is the measured value with a margin (docs/MODELS.md "Export to the RGL format").
struct Bound {
    ModelKind kind;
    double nodes, between, albedo;
};

TEST(RglExport, ReadBackMatchesTheModels) {
    const double lambda = 550;
    for (const Bound& bound : {Bound{ModelKind::ghs, 0.012, 0.025, 0.012}, Bound{ModelKind::ghs_ssa, 0.021, 0.024, 0.003},
                               Bound{ModelKind::ggx, 0.02, 0.02, 0.003}, Bound{ModelKind::two_scale, 0.14, 0.42, 0.035}}) {
        ModelOptions mo = test::kc_options(bound.kind, 0.08, 1.5, 3.5);
        mo.material = "Au";
        const auto model = make_bsdf(mo);
        const RglExportOptions o = fast(9);  // nodes every 10 degrees
        const Errors at_nodes = measure(*model, o, {0, 30, 60}, 0, lambda);
        const Errors between = measure(*model, o, {15, 45}, 0, lambda);
        std::printf("%s: at nodes %.4f (%s; albedo %.4f), between %.4f (%s; albedo %.4f)\n", model->name().c_str(),
                    at_nodes.worst, at_nodes.where.c_str(), at_nodes.albedo, between.worst, between.where.c_str(),
                    between.albedo);
        EXPECT_LT(at_nodes.worst, bound.nodes) << model->name();
        EXPECT_LT(between.worst, bound.between) << model->name();
        EXPECT_LT(std::max(at_nodes.albedo, between.albedo), bound.albedo) << model->name();
    }
}

// An anisotropic surface (elliptical KC, lay at 30 degrees): phi_i spans [-pi, pi] (pbrt-v4 reads no folded file);
// incidences at azimuths on and off the file's phi_i nodes.
TEST(RglExport, AnisotropicReadBack) {
    ModelOptions mo = test::kc_options(ModelKind::ggx, 0.08, 3.0, 3.5);
    mo.surface.corr_length_v = 1.0;
    mo.surface.lay_angle = 30;
    mo.material = "Au";
    const auto model = make_bsdf(mo);
    ASSERT_FALSE(model->isotropic());
    RglExportOptions o = fast(9);
    o.phi_i_count = 9;
    o.ndf_resolution = 64;
    const Errors on = measure(*model, o, {30}, -45, 550);
    const Errors off = measure(*model, o, {30, 50}, 100, 550);
    std::printf("anisotropic ggx_stats: on nodes %.4f (%s; albedo %.4f), off %.4f (%s; albedo %.4f)\n", on.worst,
                on.where.c_str(), on.albedo, off.worst, off.where.c_str(), off.albedo);
    // Measured: 5.3 % on nodes, 3.8 % off them, both at theta_o 78-80 (9 azimuths over 360 degrees; before the
    // lobe-adapted warp, 21 / 14 % with 9 over 180); albedo 0.16 / 0.19 %.
    EXPECT_LT(on.worst, 0.065);
    EXPECT_LT(off.worst, 0.05);
    EXPECT_LT(std::max(on.albedo, off.albedo), 0.02);
}

// rgl_export_bytes (the size `brdf export` announces before the work) against the written file, isotropic and
// anisotropic, spectral and rgb: within the header and 1-D fields' few kilobytes.
TEST(RglExport, AnnouncedSizeIsTheFiles) {
    ModelOptions mo = test::kc_options(ModelKind::ggx, 0.08, 3.0, 3.5);
    mo.material = "Au";
    const auto iso = make_bsdf(mo);
    mo.surface.corr_length_v = 1.0;
    const auto aniso = make_bsdf(mo);
    const auto path = std::filesystem::temp_directory_path() / ("rgl_size_" + std::to_string(::getpid()) + ".bsdf");
    for (const Bsdf* model : {iso.get(), aniso.get()})
        for (bool rgb : {false, true}) {
            RglExportOptions o = fast(4);
            o.phi_i_count = 5, o.ndf_resolution = 24, o.sample_resolution = 12, o.rgb = rgb;
            const RglData data = export_rgl(*model, o, "test");
            write_rgl(path, data);
            const double announced = rgl_export_bytes(o, model->isotropic(), data.theta_i.size());
            const double written = double(std::filesystem::file_size(path));
            EXPECT_GT(written, announced) << model->isotropic() << rgb;
            EXPECT_LT(written, announced + 4096) << model->isotropic() << rgb;
        }
    std::filesystem::remove(path);
}

// rgl_accuracy (what `brdf export` prints and holds against --tolerance) against this file's own grid measure: both
// see a fine export within a few percent and a coarse one (6 x 6 samples, NDF 12) far off.
TEST(RglExport, AccuracyReportAgreesWithTheGrid) {
    ModelOptions mo = test::kc_options(ModelKind::ggx, 0.08, 1.5, 3.5);
    mo.material = "Au";
    const auto model = make_bsdf(mo);
    RglExportOptions fine = fast(9), coarse = fast(9);
    coarse.sample_resolution = 6, coarse.ndf_resolution = 12;
    for (const RglExportOptions& o : {fine, coarse}) {
        const RglMeasuredBsdf back(export_rgl(*model, o, "test"));
        const RglAccuracy acc = rgl_accuracy(*model, back, o.theta_i_max_deg, {500, 550, 600}, false, 12, 128);
        const Errors grid = measure(*model, o, {15, 45}, 0, 550);
        std::printf("sample resolution %d: rgl_accuracy %.4f (rms %.4f, %zu directions), grid %.4f\n",
                    o.sample_resolution, acc.worst, acc.rms, acc.compared, grid.worst);
        EXPECT_GT(acc.compared, 1000u);
        if (o.sample_resolution == fine.sample_resolution) {
            EXPECT_LT(acc.worst, 0.05);
            EXPECT_LT(grid.worst, 0.05);
        } else {
            EXPECT_GT(acc.worst, 0.2);
            EXPECT_GT(grid.worst, 0.2);
        }
    }
}

// With a tolerance, export_rgl adds incidences where the file misses the model between two of them: the photo-setup
// plate's GHS lobe (Al, sigma 0.15 um) toward grazing incidence, which 9 uniform incidences miss by tens of percent.
TEST(RglExport, IncidencesAddedWhereTheLobeChangesFast) {
    ModelOptions mo = test::kc_options(ModelKind::ghs, 0.15, 4, 4);
    mo.material = "Al";
    const auto model = make_bsdf(mo);
    RglExportOptions o = fast(9);
    const RglMeasuredBsdf uniform(export_rgl(*model, o, "test"));
    o.tolerance_percent = 2;
    const RglData refined_data = export_rgl(*model, o, "test");
    const RglMeasuredBsdf refined(refined_data);
    const RglAccuracy before = rgl_accuracy(*model, uniform, 80, {500, 550, 600}, false, 16, 128);
    const RglAccuracy after = rgl_accuracy(*model, refined, 80, {500, 550, 600}, false, 16, 128);
    std::printf("9 uniform incidences: %.4f (theta_i %.1f); %zu after refinement: %.4f (theta_i %.1f)\n", before.worst,
                before.theta_i_deg, refined_data.theta_i.size(), after.worst, after.theta_i_deg);
    EXPECT_GT(refined_data.theta_i.size(), 9u);
    EXPECT_LT(after.worst, 0.5 * before.worst);
}

// The coherent specular part carried as a narrow lobe (brdf export --specular-lobe): the lobe's albedo is the delta's
// (the test's own quadrature, fine about the mirror direction), and a file exported with it has the model's whole
// albedo, delta included, at the file's incidence nodes (a smooth surface, sigma 0.02 um on Au: the delta is 70-95 %
// of the albedo).
TEST(RglExport, SpecularLobeCarriesTheDeltasEnergy) {
    ModelOptions mo = test::kc_options(ModelKind::ghs, 0.02, 2, 3);
    mo.material = "Au";
    const auto model = make_bsdf(mo);
    const SpecularAsLobe lobe(*model, 0.5 * kDegree);
    for (double theta : {0.0, 40.0, 70.0}) {
        const Vec3 wi = spherical_direction(theta * kDegree, 0);
        // Polar grid about the mirror direction r: offsets up to 4 degrees (8 standard deviations), midpoint rule.
        const Vec3 r{-wi.x, -wi.y, wi.z};
        const Vec3 t1 = theta > 0 ? normalize(Vec3{r.z, 0, -r.x}) : Vec3{1, 0, 0}, t2 = cross(r, t1);
        double sum = 0;
        const int na = 400, nb = 64;
        for (int a = 0; a < na; ++a)
            for (int b = 0; b < nb; ++b) {
                const double psi = (a + 0.5) * 4 * kDegree / na, phi = (b + 0.5) * kTwoPi / nb;
                const Vec3 wo = r * std::cos(psi) + (t1 * std::cos(phi) + t2 * std::sin(phi)) * std::sin(psi);
                sum += (lobe.eval(wi, wo, 550) - model->eval(wi, wo, 550)) * wo.z * std::sin(psi) * (4 * kDegree / na) *
                       (kTwoPi / nb);
            }
        EXPECT_NEAR(sum / model->delta_reflectance(wi, 550), 1.0, 1e-3) << theta;
    }
    RglExportOptions o = fast(9);
    o.tolerance_percent = 2;
    o.mirror_exclusion_rad = lobe.core_rad();  // as brdf export: the refinement leaves the lobe's core out
    const RglData data = export_rgl(lobe, o, "test");
    const RglMeasuredBsdf back(data);
    for (double theta : {0.0, 40.0, 70.0}) {
        const auto a_model = directional_albedo(*model, theta * kDegree, 550);
        const auto a_back = directional_albedo(back, theta * kDegree, 550);
        std::printf("theta_i %.0f: model %.5f (delta %.5f), file %.5f (%zu incidences)\n", theta, a_model.total(),
                    a_model.specular, a_back.total(), data.theta_i.size());
        EXPECT_NEAR(a_back.total() / a_model.total(), 1.0, 0.02) << theta;
    }
}
