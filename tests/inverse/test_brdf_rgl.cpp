// RGL measured files as fit data (inverse::read_brdf_rgl): the rows of a file the test writes are the file's values at
// its sample nodes, where the exported file is exact, so they equal the model it was made from (its own eval at those
// directions); the real files of RGL's database (skipped when absent) give rows within the format's invariants.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/rgl_export.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/inverse/brdf_data.hpp"

namespace ss = surfscatter;

namespace {

const std::filesystem::path kRgl = std::filesystem::path(SURFSCATTER_SHARED_DATA) / "realdata" / "rgl";

}  // namespace

TEST(BrdfRgl, RowsAreTheModelAtTheFilesNodes) {
    ss::bsdf::ModelOptions mo;
    mo.model = ss::bsdf::ModelKind::ggx;
    mo.surface.psd = ss::bsdf::PsdKind::kc;
    mo.surface.sigma = 0.1, mo.surface.corr_length = 1.5, mo.surface.gamma = 3.5;
    mo.material = "Au";
    const auto model = ss::bsdf::make_bsdf(mo);
    ss::bsdf::RglExportOptions o;
    o.theta_i_count = 5, o.theta_i_max_deg = 80, o.sample_resolution = 16, o.ndf_resolution = 32;
    o.lambda_min_nm = 400, o.lambda_max_nm = 700, o.lambda_step_nm = 50, o.threads = 2;
    const auto dir = std::filesystem::temp_directory_path() / ("brdf_rgl_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "gold.bsdf").string();
    ss::bsdf::write_rgl(path, ss::bsdf::export_rgl(*model, o, "test"));
    const ss::inverse::BrdfData data = ss::inverse::read_brdf_rgl(path, {450, 550, 650}, 2000);
    // 5 incidences x 16 x 16 nodes (stride 1 fits in 2000 / 5 = 400), less those beyond 89 degrees, at 3 wavelengths.
    EXPECT_GT(data.size(), 5u * 100 * 3);
    EXPECT_LE(data.size(), 5u * 256 * 3);
    double worst = 0;
    for (std::size_t k = 0; k < data.size(); ++k) {
        const auto wi = ss::spherical_direction(data.theta_i_deg[k] * ss::kDegree, data.phi_i_deg[k] * ss::kDegree);
        const auto wo = ss::spherical_direction(data.theta_o_deg[k] * ss::kDegree, data.phi_o_deg[k] * ss::kDegree);
        worst = std::max(worst, std::abs(data.brdf[k] / model->eval(wi, wo, data.wavelength_nm[k]) - 1));
    }
    std::printf("%zu rows, worst relative difference from the model %.2e\n", data.size(), worst);
    EXPECT_LT(worst, 1e-4);  // float32 tables (measured 1.4e-6)
    const ss::inverse::BrdfData thin = ss::inverse::read_brdf_rgl(path, {550}, 100);
    EXPECT_LE(thin.size(), 100u);  // every 2nd node per side: 5 x 8 x 8 = 320 > 100, every 4th: 5 x 16 = 80
    EXPECT_THROW(ss::inverse::read_brdf_rgl(path, {300}, 100), ss::Error);  // outside 400-700 nm
    std::filesystem::remove_all(dir);
}

TEST(BrdfRgl, RealFiles) {
    if (!std::filesystem::exists(kRgl)) GTEST_SKIP() << kRgl << " absent";
    for (const auto& entry : std::filesystem::directory_iterator(kRgl)) {
        if (entry.path().extension() != ".bsdf") continue;
        const ss::inverse::BrdfData data = ss::inverse::read_brdf_rgl(entry.path().string(), {450, 550, 650});
        // 8 incidences of which 7 are below 89 degrees; at most 1000 directions.
        EXPECT_GT(data.size(), 300u) << entry.path();
        EXPECT_LE(data.size(), 3000u) << entry.path();
        for (std::size_t k = 0; k < data.size(); ++k) {
            ASSERT_TRUE(data.brdf[k] > 0 && std::isfinite(data.brdf[k])) << entry.path() << " row " << k;
            ASSERT_LT(data.theta_o_deg[k], 89.0);
            ASSERT_LT(data.theta_i_deg[k], 89.0);
        }
    }
}
