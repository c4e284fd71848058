// Chi-square tests of every model's sampler over theta_i {0, 30, 60, 80}, g0 from 0.01 to 1000 and several gamma;
// pdf() equals the pdf sample() returns; weights equal f cos / pdf; the density never exceeds unit mass.
#include <gtest/gtest.h>

#include <vector>

#include "chi2_harness.hpp"
#include "model_fixtures.hpp"

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

TEST(Samplers, TwoScale) {
    // Macro slopes need gamma > 3 or a cutoff: the split provides the cutoff.
    auto cases = cases_for(ModelKind::two_scale, GhsMethod::exact, {3.0}, {0.1, 10});
    for (auto& c : cases) c.options.cutoff_wavelengths = 5;
    run(cases, 200000);
}
