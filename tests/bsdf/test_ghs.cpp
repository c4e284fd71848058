// Full GHS (exact S_g and refit series): published table, furnace, reciprocity, limits, samplers.
#include <gtest/gtest.h>

#include <cmath>

#include "chi2_harness.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

const GhsBsdf& as_ghs(const Bsdf& b) { return dynamic_cast<const GhsBsdf&>(b); }

}  // namespace

// THEORY 1.6(a): Krywonos 2011 / Johansen Gaussian-ACV case, perfect conductor, in-plane specular side.
TEST(Ghs, ReproducesTheKrywonosGaussianTable) {
    ModelOptions o;
    o.model = ModelKind::ghs;
    o.surface.psd = PsdKind::gaussian;
    o.surface.sigma = 2.27;
    o.surface.corr_length = 20.9;
    const auto bsdf = make_bsdf(o);
    const auto& ghs = as_ghs(*bsdf);
    const double lambda = 10600.0;
    struct Row { double theta_i, sigma_rel, K, brdf[9]; };
    const Row rows[] = {
        {20, 2.2700, 1.1001, {0.9752, 1.8916, 2.5811, 2.1710, 1.2331, 0.5425, 0.2008, 0.0678, 0.0227}},
        {40, 2.2687, 1.1215, {0.1375, 0.4638, 1.2572, 2.7448, 4.1787, 3.6593, 2.1083, 1.0052, 0.4650}},
        {60, 2.1136, 1.2025, {0.0065, 0.0382, 0.1795, 0.6855, 2.2339, 5.5391, 7.5915, 6.1411, 3.8230}},
        {70, 1.8727, 1.1919, {0.0006, 0.0050, 0.0338, 0.1816, 0.8056, 2.9091, 5.6061, 5.4923, 3.4708}},
    };
    double worst = 0;
    for (const Row& r : rows) {
        const Vec3 wi = spherical_direction(r.theta_i * kDegree, 0.0);
        EXPECT_NEAR(ghs.sigma(wi.z, lambda), r.sigma_rel, 0.01 * r.sigma_rel) << r.theta_i;
        EXPECT_NEAR(ghs.normalization(wi.z, lambda), r.K, 0.01 * r.K) << r.theta_i;
        for (int j = 0; j < 9; ++j) {
            const Vec3 wo = spherical_direction(10.0 * j * kDegree, kPi);
            const double f = bsdf->eval(wi, wo, lambda);
            // The table has 4 decimals: the smallest entries are compared to their rounding.
            const double tol = std::max(0.01 * r.brdf[j], 0.6e-4);
            EXPECT_NEAR(f, r.brdf[j], tol) << "theta_i " << r.theta_i << " theta_s " << 10 * j;
            worst = std::max(worst, std::abs(f / r.brdf[j] - 1));
        }
    }
    RecordProperty("worst_relative_error", std::to_string(worst));
}

TEST(Ghs, WhiteFurnaceAndReciprocity) {
    const double lambda = 1000.0;
    for (double gamma : {2.5, 3.0, 4.0})
        for (double sigma : {0.01, 0.1, 0.5, 2.0}) {
            const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, sigma, 1.0, gamma));
            const auto& ghs = as_ghs(*bsdf);
            for (double t = 0; t <= 85; t += 17) {
                const Vec3 wi = spherical_direction(t * kDegree, 0.4);
                const double albedo = test::directional_albedo(*bsdf, wi, lambda, 300, 256);
                EXPECT_NEAR(albedo, 1.0, 5e-3) << "gamma " << gamma << " sigma " << sigma << " theta_i " << t;
                // The core lobe is symmetric in i <-> o (with the same sigma).
                const Vec3 wo = spherical_direction(40 * kDegree, 2.0);
                const double a = ghs.core_lobe(wi, wo, lambda, sigma), b = ghs.core_lobe(wo, wi, lambda, sigma);
                EXPECT_NEAR(a, b, 1e-12 * std::max(a, b));
            }
        }
}

// THEORY 1.5: gamma = 4, large g: k^2 S_g -> P22(s) / (cos i + cos o)^2, P22 Gaussian with alpha^2 = 2 sigma^2/L^2.
// The lobe shape depends on sigma only through g, so the table of one KC(gamma = 4, L) serves any sigma.
TEST(Ghs, Gamma4LargeGApproachesGeometricOptics) {
    const double length = 20.0, lambda = 500.0, sigma = 12.6;  // g = (k sigma (ci + co))^2 ~ 2e4 .. 1e5
    const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, 0.05, length, 4.0));
    const auto& ghs = as_ghs(*bsdf);
    const double a2 = 2 * sigma * sigma / (length * length);
    double worst = 0;
    int compared = 0;
    for (double t : {0.0, 30.0, 60.0})
        for (double dt : {-40.0, -20.0, -8.0, 0.0, 5.0, 15.0, 25.0}) {
            const double to = t + dt;
            if (std::abs(to) >= 89) continue;
            const Vec3 wi = spherical_direction(t * kDegree, 0.0);
            const Vec3 wo = spherical_direction(std::abs(to) * kDegree, to >= 0 ? kPi : 0.0);
            const double c = wi.z + wo.z;
            const double sx = (wi.x + wo.x) / c, sy = (wi.y + wo.y) / c;
            const double expected = std::exp(-(sx * sx + sy * sy) / a2) / (kPi * a2 * c * c);
            const double got = ghs.core_lobe(wi, wo, lambda, sigma);
            worst = std::max(worst, std::abs(got / expected - 1));
            ++compared;
        }
    EXPECT_GT(compared, 15);
    EXPECT_LT(worst, 0.02);
}
