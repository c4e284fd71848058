// GGX microfacet conductor: sampler chi-square, pdf/weight consistency, energy bound, kc_link roughness.
#include <gtest/gtest.h>

#include <cmath>

#include "chi2_harness.hpp"
#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/bsdf/microfacet.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

TEST(Ggx, NdfIsNormalisedAndVisibleNormalsToo) {
    for (double alpha : {0.1, 0.3, 1.0}) {
        const GgxDistribution ggx(alpha);
        const Vec3 wi = spherical_direction(60 * kDegree, 0.3);
        double projected = 0, visible = 0;
        const int nt = 8000, np = 64;
        for (int i = 0; i < nt; ++i)
            for (int j = 0; j < np; ++j) {
                // Midpoint rule in (cos theta, phi).
                const double c = (i + 0.5) / nt, phi = kTwoPi * (j + 0.5) / np;
                const double s = std::sqrt(1 - c * c);
                const Vec3 h(s * std::cos(phi), s * std::sin(phi), c);
                const double dw = (1.0 / nt) * (kTwoPi / np);
                projected += ggx.D(h) * c * dw;
                visible += ggx.visible_density(wi, h) * dw;
            }
        EXPECT_NEAR(projected, 1.0, 2e-3) << alpha;
        EXPECT_NEAR(visible, 1.0, 2e-3) << alpha;
    }
}

TEST(Ggx, ChiSquareAndConsistency) {
    const auto perfect = material::Conductor::perfect();
    const double thetas[] = {0, 30, 60, 80};
    const double alphas[] = {0.1, 0.4, 0.9};
    const double level = test::sidak(0.01, 12);
    for (double alpha : alphas) {
        const GgxBsdf bsdf(perfect, alpha);
        for (double t : thetas) {
            const Vec3 wi = spherical_direction(t * kDegree, 0.7);
            const auto r = test::chi2_test(bsdf, wi, 550.0, 400000);
            EXPECT_GT(r.p_value, level) << "alpha " << alpha << " theta_i " << t << ": " << r.summary();
            EXPECT_LT(r.pdf_mismatch, 1e-9) << r.summary();
            EXPECT_LT(r.weight_mismatch, 1e-9) << r.summary();
            EXPECT_LE(r.expected_total, 1.0 + 1e-3) << r.summary();
        }
    }
}

TEST(Ggx, KcLinkRoughness) {
    // alpha^2 = 1 / (1 + 4 k^2 L^2): L = 1 um at 628.3 nm (k = 10 rad/um) gives 1/sqrt(401).
    EXPECT_NEAR(kc_link_alpha(1.0, 200 * kPi), 1.0 / std::sqrt(401.0), 1e-12);
}
