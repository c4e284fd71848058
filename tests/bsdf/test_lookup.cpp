// The GHS per-(theta_i, lambda) lookup: NodeAxis, the accuracy of the tabulated sigma and N against their direct
// computation, the lock-free lazily built tables under concurrent first use, and their disk cache.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <unistd.h>

#include "model_fixtures.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/node_axis.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

TEST(NodeAxis, NodesOnCellEdgesAndLinearBetween) {
    std::vector<double> wanted{0.1};
    while (wanted.back() < 1e8) wanted.push_back(wanted.back() * std::exp(0.02));
    const NodeAxis axis(wanted);
    ASSERT_EQ(axis.size(), int(wanted.size()));
    for (int j = 0; j < axis.size(); ++j) {
        EXPECT_NEAR(axis.node(j) / wanted[j], 1.0, 2e-3) << j;  // half a cell: 2^-9 relative
        if (j + 1 < axis.size()) {
            const NodeAxis::Position at = axis.position(axis.node(j));
            EXPECT_EQ(at.interval, j);
            EXPECT_EQ(at.t, 0.0);
            const double mid = 0.5 * (axis.node(j) + axis.node(j + 1));
            EXPECT_NEAR(axis.position(mid).t, 0.5, 1e-12) << j;
        }
    }
    const NodeAxis::Position last = axis.position(axis.node(axis.size() - 1));
    EXPECT_EQ(last.interval, axis.size() - 2);
    EXPECT_NEAR(last.t, 1.0, 1e-12);
}

// sigma and N between nodes (incidence and wavelength) against direct(), theta_i up to 89.99 deg, for surfaces whose K
// spans six decades over theta_i (fractal gamma = 1.5), a rough surface at grazing (sigma 2 um, L 10 um) and large
// k L (1100 and 5700). Measured maxima: sigma 3.0e-4 (kL 5700 at 89.1 deg; elsewhere < 1e-4), N 5.4e-4; the albedo
// error they make, (1 - e^{-g0}) dN/N, at most 2.4e-4. The previous lookup (52 nodes to 89.5 deg, linear in cos theta_i
// and in N) had sigma 8.6e-4 at 79 deg and 4.3e-3 at 88.8 deg, N 1.5 % at 57 deg (gamma 1.5) and 25x beyond 89.5 deg.
TEST(Ghs, TabulatedSigmaAndNormalizationMatchDirectValues) {
    struct Surface {
        ModelOptions options;
        double lambda;
    };
    ModelOptions gauss;
    gauss.surface.psd = PsdKind::gaussian;
    gauss.surface.sigma = 2.27;
    gauss.surface.corr_length = 20.9;
    const Surface surfaces[] = {{test::kc_options(ModelKind::ghs, 0.138, 1.0, 3.0), 706.85},
                                {test::kc_options(ModelKind::ghs, 0.2, 0.5, 2.5), 451.7},
                                {gauss, 10600.0},
                                {test::kc_options(ModelKind::ghs, 1.0, 2.0, 1.5), 553.0},
                                {test::kc_options(ModelKind::ghs, 2.0, 10.0, 3.0), 553.0},
                                {test::kc_options(ModelKind::ghs, 0.3, 200.0, 3.0), 553.0},
                                {test::kc_options(ModelKind::ghs, 0.05, 500.0, 4.0), 553.0}};
    for (const Surface& s : surfaces) {
        const auto bsdf = make_bsdf(s.options);
        const auto& ghs = dynamic_cast<const GhsBsdf&>(*bsdf);
        double sigma_error = 0, norm_error = 0, albedo_error = 0;
        for (int i = 0; i <= 200; ++i) {
            const double theta = 89.99 * (i + 0.37) / 200.37;
            const GhsBsdf::Direct d = ghs.direct(theta * kDegree, s.lambda);
            const double c = std::cos(theta * kDegree);
            sigma_error = std::max(sigma_error, std::abs(ghs.sigma(c, s.lambda) / d.sigma - 1));
            const double e = std::abs(ghs.normalization(c, s.lambda) / d.norm - 1);
            norm_error = std::max(norm_error, e);
            albedo_error = std::max(albedo_error, -std::expm1(-std::pow(2 * wavenumber(s.lambda) * d.sigma * c, 2)) * e);
        }
        std::printf("lookup vs direct, %s at %g nm: sigma %.2e, N %.2e, albedo %.2e\n", s.options.surface.psd == PsdKind::kc ?
                    fmt::format("KC sigma {} L {} gamma {}", s.options.surface.sigma, s.options.surface.corr_length,
                                s.options.surface.gamma).c_str() : "Gaussian ACV", s.lambda, sigma_error, norm_error,
                    albedo_error);
        EXPECT_LT(sigma_error, 5e-4) << s.lambda;
        EXPECT_LT(norm_error, 1e-3) << s.lambda;
        EXPECT_LT(albedo_error, 5e-4) << s.lambda;
    }
}

TEST(Ghs, TablesBuiltConcurrentlyGiveTheSameValues) {
    const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, 0.1, 1.0, 3.0));
    const Vec3 wi = spherical_direction(40 * kDegree, 0.2), wo = spherical_direction(25 * kDegree, 2.5);
    const std::vector<double> lambdas{401.0, 455.5, 512.25, 587.0, 650.5, 733.0};
    std::vector<std::vector<double>> got(4, std::vector<double>(lambdas.size()));
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < got.size(); ++t)
        threads.emplace_back([&, t] {
            for (std::size_t i = 0; i < lambdas.size(); ++i)
                got[t][i] = bsdf->eval(wi, wo, lambdas[(i + t) % lambdas.size()]);
        });
    for (auto& t : threads) t.join();
    for (std::size_t i = 0; i < lambdas.size(); ++i) {
        const double expected = bsdf->eval(wi, wo, lambdas[i]);
        EXPECT_GT(expected, 0.0);
        for (std::size_t t = 0; t < got.size(); ++t)
            EXPECT_EQ(got[t][(i + lambdas.size() - t) % lambdas.size()], expected);
    }
}

// The per-wavelength tables are kept on disk: a second BSDF gets the same numbers bit for bit without rewriting the
// files, and a corrupt file is rebuilt (the same file again).
TEST(Ghs, TablesCachedOnDiskGiveTheSameValues) {
    const auto dir = std::filesystem::temp_directory_path() / fmt::format("surfscatter-ghs-cache-{}", getpid());
    std::filesystem::remove_all(dir);
    const char* previous = std::getenv("SURFSCATTER_CACHE_DIR");
    const std::string restore = previous ? previous : "";
    setenv("SURFSCATTER_CACHE_DIR", dir.c_str(), 1);
    const auto values = [] {
        const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, 0.1, 1.0, 3.0));
        const auto& ghs = dynamic_cast<const GhsBsdf&>(*bsdf);
        std::vector<double> v;
        for (double lambda : {401.0, 587.0})
            for (double c : {0.05, 0.5, 0.99}) {
                v.push_back(ghs.sigma(c, lambda));
                v.push_back(ghs.normalization(c, lambda));
            }
        return v;
    };
    const auto files = [&] {
        std::map<std::string, std::string> contents;
        for (const auto& entry : std::filesystem::directory_iterator(dir))
            if (entry.path().filename().string().starts_with("ghs-incidence")) {
                std::ifstream in(entry.path(), std::ios::binary);
                contents[entry.path().string()] = std::string(std::istreambuf_iterator<char>(in), {});
            }
        return contents;
    };
    const std::vector<double> built = values();
    const auto written = files();
    EXPECT_EQ(written.size(), 4u);  // two wavelength nodes around each wavelength
    std::map<std::string, std::filesystem::file_time_type> times;
    for (const auto& [path, bytes] : written) times[path] = std::filesystem::last_write_time(path);
    EXPECT_EQ(values(), built);
    for (const auto& [path, time] : times) EXPECT_EQ(std::filesystem::last_write_time(path), time) << path;
    for (const auto& [path, bytes] : written) {
        std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(static_cast<std::streamoff>(bytes.size() / 2));
        f.write("garbage!", 8);
    }
    EXPECT_EQ(values(), built);
    EXPECT_EQ(files(), written);
    if (restore.empty()) unsetenv("SURFSCATTER_CACHE_DIR");
    else setenv("SURFSCATTER_CACHE_DIR", restore.c_str(), 1);
    std::filesystem::remove_all(dir);
}

TEST(Ghs, WavelengthOutsideTheTablesIsAnError) {
    const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, 0.1, 1.0, 3.0));
    const Vec3 wi = spherical_direction(0.3, 0.0), wo = spherical_direction(0.5, 2.0);
    EXPECT_THROW(bsdf->eval(wi, wo, 0.01), Error);
    EXPECT_THROW(bsdf->eval(wi, wo, 2e8), Error);
    EXPECT_THROW(bsdf->eval(wi, wo, std::nan("")), Error);
}

// eval against the BRDF assembled from its parts at many (theta_i, lambda) off the nodes, outgoing directions from the
// sampler: (1) R N k^2 S_g with the lookup's own sigma and N, S_g through the density path (core_lobe): checks eval's
// single exponential of ln N + ln S_g (exact core) and its product exp(ln N) density (other cores); (2) the same with
// sigma and N computed directly at (theta_i, lambda) (direct()): the lookup's whole error in the BRDF, as the relative
// L1 distance int |f - f_direct| cos / int f_direct cos over the scattered lobe. Exact core (KC, Gaussian ACV), the
// refit series and the first-order (SSA) core. Measured: (1) < 2e-14, (2) 4e-4 at most.
TEST(Ghs, EvalMatchesTheBrdfBuiltFromDirectValues) {
    ModelOptions gauss;
    gauss.surface.psd = PsdKind::gaussian;
    gauss.surface.sigma = 0.3;
    gauss.surface.corr_length = 3.0;
    auto refit = test::kc_options(ModelKind::ghs, 0.05, 2.0, 2.5);
    refit.method = GhsMethod::refit;
    const ModelOptions surfaces[] = {test::kc_options(ModelKind::ghs, 0.138, 1.0, 3.0),
                                     test::kc_options(ModelKind::ghs, 1.0, 2.0, 1.5), gauss, refit,
                                     test::kc_options(ModelKind::ghs_ssa, 0.05, 2.0, 3.0)};
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (const ModelOptions& o : surfaces) {
        const auto bsdf = make_bsdf(o);
        const auto& ghs = dynamic_cast<const GhsBsdf&>(*bsdf);
        double parts_error = 0, worst_l1 = 0;
        for (int i = 0; i < 60; ++i) {
            // Wavelengths within 2 % above three bases: between nodes (2 % apart), and few tables to build.
            const double theta = 89.9 * uniform(rng);
            const double lambda = (i % 3 == 0 ? 405.0 : i % 3 == 1 ? 550.0 : 790.0) * (1 + 0.02 * uniform(rng));
            const Vec3 wi = spherical_direction(theta * kDegree, 0.3);
            const double r = material::Conductor::from_name(o.material).reflectance(wi.z, lambda);
            const GhsBsdf::Direct d = ghs.direct(theta * kDegree, lambda);
            double diff = 0, total = 0;
            for (int j = 0; j < 50; ++j) {
                const auto s = bsdf->sample(wi, lambda, 0.999999 * uniform(rng), {uniform(rng), uniform(rng)});
                if (!s || s->delta) continue;
                const double f = bsdf->eval(wi, s->wo, lambda);
                const double parts = r * ghs.normalization(wi.z, lambda) *
                                     ghs.core_lobe(wi, s->wo, lambda, ghs.sigma(wi.z, lambda));
                if (parts > 0) parts_error = std::max(parts_error, std::abs(f / parts - 1));
                const double direct = r * d.norm * ghs.core_lobe(wi, s->wo, lambda, d.sigma);
                diff += std::abs(f - direct) * s->wo.z / s->pdf;
                total += direct * s->wo.z / s->pdf;
            }
            if (total > 0) worst_l1 = std::max(worst_l1, diff / total);
        }
        std::printf("%s sigma %g: eval against its parts %.2e, L1 against direct sigma and N %.2e\n",
                    to_string(o.model).c_str(), o.surface.sigma, parts_error, worst_l1);
        EXPECT_LT(parts_error, 1e-13) << o.surface.sigma;
        EXPECT_LT(worst_l1, 2e-3) << o.surface.sigma;
    }
}
