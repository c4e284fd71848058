// Chi-square tests of every model's sampler over theta_i {0, 30, 60, 80}, g0 from 0.01 to 1000 and several gamma;
// pdf() equals the pdf sample() returns; weights equal f cos / pdf; the density never exceeds unit mass.
#include <gtest/gtest.h>

#include <vector>

#include "chi2_harness.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

struct Case {
    ModelOptions options;
    double theta_i;
    double g;
};

constexpr double kLambda = 1000.0;  // k L = 6.3 with L = 1 um: lobes broader than the histogram cells

std::vector<Case> cases_for(ModelKind model, GhsMethod method, const std::vector<double>& gammas,
                            const std::vector<double>& gs) {
    std::vector<Case> cases;
    for (double gamma : gammas)
        for (double g : gs)
            for (double t : {0.0, 30.0, 60.0, 80.0}) {
                ModelOptions o = test::kc_options(model, test::sigma_for_g(g, kLambda, t), 1.0, gamma);
                o.method = method;
                cases.push_back({o, t, g});
            }
    return cases;
}

void run(const std::vector<Case>& cases, long samples) {
    const double level = test::sidak(0.01, int(cases.size()));
    for (const Case& c : cases) {
        const auto bsdf = make_bsdf(c.options);
        const Vec3 wi = spherical_direction(c.theta_i * kDegree, 1.1);
        const auto r = test::chi2_test(*bsdf, wi, kLambda, samples, 45, 90);
        const std::string what = bsdf->name() + " gamma " + std::to_string(c.options.surface.gamma) + " g " +
                                 std::to_string(c.g) + " theta_i " + std::to_string(c.theta_i) + ": " + r.summary();
        EXPECT_GT(r.p_value, level) << what;
        EXPECT_LT(r.pdf_mismatch, 1e-6) << what;
        EXPECT_LT(r.weight_mismatch, 1e-6) << what;
        EXPECT_LE(r.expected_total, 1.0 + 2e-3) << what;
    }
}

}  // namespace

// 1e6 samples where the lobe and the delta share the energy (g ~ 1-30, gamma = 3); 2e5 elsewhere (test time).
TEST(Samplers, GhsExact) {
    run(cases_for(ModelKind::ghs, GhsMethod::exact, {3.0}, {1, 30}), 1000000);
    run(cases_for(ModelKind::ghs, GhsMethod::exact, {3.0}, {0.01, 1000}), 200000);
    run(cases_for(ModelKind::ghs, GhsMethod::exact, {2.5, 4.0}, {0.01, 3, 1000}), 200000);
}

TEST(Samplers, GhsRefit) { run(cases_for(ModelKind::ghs, GhsMethod::refit, {2.5, 4.0}, {0.01, 10}), 150000); }

TEST(Samplers, GhsSsa) { run(cases_for(ModelKind::ghs_ssa, GhsMethod::exact, {2.5, 3.0}, {0.01, 1, 30}), 200000); }

// The two-scale sampler at the supplemental's cutoffs (N = 20, 100, 150) and micro g0 from 0.01 to 100, binned in the
// lobe's own coordinates (chi2_test_wedge: |zeta|/k on log bins with an edge at the micro lobe's hole zeta_c/k),
// which resolve the macro spike and the hole that a (theta, phi) grid would average away.
TEST(Samplers, TwoScaleAtThePaperCutoffs) {
    const double lambda = 550.0, length = 1.0, gamma = 3.0, k = wavenumber(lambda);
    std::vector<std::pair<ModelOptions, double>> cases;
    for (double n : {20.0, 100.0, 150.0})
        for (double g : {0.01, 1.0, 100.0})
            for (double t : {0.0, 30.0, 60.0, 80.0}) {
                const double zeta_c = k / n;
                const double micro_fraction = std::pow(1.0 + length * length * zeta_c * zeta_c, -0.5 * (gamma - 1.0));
                auto o = test::kc_options(ModelKind::two_scale, test::sigma_for_g(g, lambda, t) / std::sqrt(micro_fraction),
                                          length, gamma);
                o.cutoff_wavelengths = n;
                cases.push_back({o, t});
            }
    const double level = test::sidak(0.01, int(cases.size()));
    for (const auto& [o, t] : cases) {
        const auto bsdf = make_bsdf(o);
        const Vec3 wi = spherical_direction(t * kDegree, 1.1);
        const double zeta_c = k / o.cutoff_wavelengths;
        const auto r = test::chi2_test_wedge(*bsdf, wi, lambda, 200000, {zeta_c / k});
        const double g0 = -std::log(dynamic_cast<const TwoScaleBsdf&>(*bsdf).micro().delta_probability(wi, lambda));
        const std::string what = "N " + std::to_string(o.cutoff_wavelengths) + " sigma " + std::to_string(o.surface.sigma) +
                                 " theta_i " + std::to_string(t) + " micro g0 " + std::to_string(g0) + ": " + r.summary();
        EXPECT_GT(r.p_value, level) << what;
        EXPECT_LT(r.pdf_mismatch, 1e-6) << what;
        EXPECT_LT(r.weight_mismatch, 1e-6) << what;
        // Every direction is proposed: the pdf's mass is 1 less what the macro sampler sends below the horizon, and
        // the pdf is positive wherever f is (a grid of directions, including inside the micro lobe's hole).
        EXPECT_NEAR(r.expected_total + double(r.failed) / 200000, 1.0, 3e-3) << what;
        int uncovered = 0;
        for (double to = 0.25; to < 90; to += 0.5)
            for (double phi = 0; phi < kTwoPi; phi += 0.1) {
                const Vec3 wo = spherical_direction(to * kDegree, phi);
                if (bsdf->eval(wi, wo, lambda) > 0 && !(bsdf->pdf(wi, wo, lambda) > 0)) ++uncovered;
            }
        for (double q : {0.1, 0.5, 0.9})
            if (const auto wo = wedge_direction(wi, q * zeta_c / k, 0.3))
                if (bsdf->eval(wi, *wo, lambda) > 0 && !(bsdf->pdf(wi, *wo, lambda) > 0)) ++uncovered;
        EXPECT_EQ(uncovered, 0) << what;
    }
}

TEST(Samplers, TwoScale) {
    // Macro slopes need gamma > 3 or a cutoff: the split provides the cutoff.
    auto cases = cases_for(ModelKind::two_scale, GhsMethod::exact, {3.0}, {0.1, 10});
    for (auto& c : cases) c.options.cutoff_wavelengths = 5;
    run(cases, 200000);
}
