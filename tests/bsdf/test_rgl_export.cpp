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

// Measured with these settings (worst relative error where f >= 1 % of the peak and theta_o <= 80 deg; albedo):
// ghs 6.2 % at nodes (near theta_o 78), 2.0 % between, albedo 0.3 / 1.1 %; ggx_stats 8.6 / 9.5 % (theta_o 79.5),
// albedo 0.2 %; ghs_ssa 50 % / 14 % next to the specular direction (its lobe there is narrower than the sample
// grid resolves), albedo 0.3 / 1.0 %; two_scale 205 % / 188 % (the macro spike and the micro lobe's hole at
// zeta_c, which a smooth table cannot hold), albedo 30 % / 8 %. Each bound is the measured value with a margin; the
// 2 % target of issue 35 holds for ghs between nodes only (docs/MODELS.md "Export to the RGL format").
struct Bound {
    ModelKind kind;
    double nodes, between, albedo;
};

TEST(RglExport, ReadBackMatchesTheModels) {
    const double lambda = 550;
    for (const Bound& bound : {Bound{ModelKind::ghs, 0.07, 0.025, 0.02}, Bound{ModelKind::ghs_ssa, 0.55, 0.16, 0.02},
                               Bound{ModelKind::ggx, 0.10, 0.11, 0.01}, Bound{ModelKind::two_scale, 2.2, 2.0, 0.35}}) {
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

// An anisotropic surface (elliptical KC, lay at 30 degrees): phi_i spans [-pi, 0] and readers fold wi by the
// 2-fold symmetry; incidences at azimuths on and off the file's phi_i nodes.
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
    // Measured: 21 % on nodes, 14 % off them, both at theta_o 79.5 (the f cos tabulation near the horizon; 1-3 %
    // below theta_o 60); albedo 0.13 / 0.07 %.
    EXPECT_LT(on.worst, 0.25);
    EXPECT_LT(off.worst, 0.17);
    EXPECT_LT(std::max(on.albedo, off.albedo), 0.02);
}
