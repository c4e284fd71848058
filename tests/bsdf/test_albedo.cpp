// Directional albedo of every model against its documented value (docs/MODELS.md), by the tests' own quadrature
// (disc_albedo.hpp): the GHS (exact and refit) and the SSA energy form carry exactly R(theta_i), the two-scale model and
// GGX at most R. A sparse version of the sweep of issue 10 (sigma 0.001-2 um, L 0.5-50 um, gamma 1.5-4, 360 and 830 nm,
// N 20 and 150, theta_i 0 to 89.99 deg; perfect conductor and gold); the full sweep is bench/table_albedo_sweep.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "disc_albedo.hpp"
#include "hemisphere_albedo.hpp"
#include "model_fixtures.hpp"
#include <fmt/format.h>

#include "surfscatter/bsdf/albedo.hpp"
#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/material/conductor.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

// A lobe with known albedo: f = a e^{-q^2/w^2} / (pi w^2) about the specular direction (q = |i_xy + o_xy|) plus the
// constant b / pi: albedo b + a when the spike lies well inside the disc (w <= (1 - sin theta_i) / 6).
class KnownLobe final : public Bsdf {
public:
    KnownLobe(double a, double w, double b) : a_(a), w_(w), b_(b) {}
    double eval(const Vec3& wi, const Vec3& wo, double) const override {
        const double q = scatter_radius(wi, wo);
        return a_ * std::exp(-q * q / (w_ * w_)) / (kPi * w_ * w_) + b_ / kPi;
    }
    std::optional<BsdfSample> sample(const Vec3&, double, double, Vec2) const override { return std::nullopt; }
    double pdf(const Vec3&, const Vec3&, double) const override { return 0; }
    std::string name() const override { return "known"; }

private:
    double a_, w_, b_;
};

}  // namespace

TEST(Albedo, QuadratureIsExactOnKnownLobes) {
    for (double theta : {0.0, 30.0, 60.0})
        for (double w : {1e-5, 1e-3, 0.02, 0.08}) {
            if (w > (1 - std::sin(theta * kDegree)) / 6) continue;
            const Vec3 wi = spherical_direction(theta * kDegree, 0.7);
            EXPECT_NEAR(test::disc_albedo(KnownLobe(0.6, w, 0.4), wi, 550.0), 1.0, 2e-7) << theta << " " << w;
        }
    EXPECT_NEAR(test::disc_albedo(KnownLobe(0.0, 1.0, 1.0), spherical_direction(89.99 * kDegree, 0), 550.0), 1.0, 1e-7);
}

TEST(Albedo, EveryModelWithinHalfAPercentOfItsDocumentedValue) {
    struct Case {
        ModelOptions options;
        std::string label;
    };
    std::vector<Case> cases;
    for (const auto& [sigma, length, gamma] : {std::tuple{0.001, 50.0, 4.0}, std::tuple{2.0, 0.5, 1.5},
                                               std::tuple{2.0, 50.0, 4.0}, std::tuple{0.1, 2.0, 3.0},
                                               std::tuple{1.0, 2.0, 1.5}, std::tuple{0.5, 10.0, 2.5}}) {
        const std::string surface = fmt::format("sigma {} L {} gamma {}", sigma, length, gamma);
        cases.push_back({test::kc_options(ModelKind::ghs, sigma, length, gamma), "ghs " + surface});
        cases.push_back({test::kc_options(ModelKind::ghs_ssa, sigma, length, gamma), "ghs_ssa " + surface});
        for (double n : {20.0, 150.0}) {
            auto o = test::kc_options(ModelKind::two_scale, sigma, length, gamma);
            o.cutoff_wavelengths = n;
            cases.push_back({o, fmt::format("two_scale N {} {}", n, surface)});
        }
        auto ggx = test::kc_options(ModelKind::ggx, sigma, length, gamma);
        ggx.alpha_from = AlphaFrom::kc_link;
        cases.push_back({ggx, "ggx kc_link " + surface});
    }
    {  // gold: the documented value is R(theta_i)
        auto o = test::kc_options(ModelKind::ghs, 0.5, 10.0, 2.5);
        o.material = "Au";
        cases.push_back({o, "ghs gold sigma 0.5 L 10 gamma 2.5"});
        o.model = ModelKind::two_scale;
        o.cutoff_wavelengths = 100;
        cases.push_back({o, "two_scale N 100 gold sigma 0.5 L 10 gamma 2.5"});
    }
    for (const Case& c : cases) {
        const auto bsdf = make_bsdf(c.options);
        const auto material = material::Conductor::from_name(c.options.material);
        double worst = 0, worst_theta = 0;
        for (double lambda : {360.0, 830.0})
            for (double theta : {0.0, 60.0, 85.0, 89.5, 89.99}) {
                const Vec3 wi = spherical_direction(theta * kDegree, 0.4);
                const double albedo = test::disc_albedo(*bsdf, wi, lambda, test::lobe_jumps(c.options, lambda));
                const double r = material.reflectance(wi.z, lambda);
                const bool exact = c.options.model == ModelKind::ghs || c.options.model == ModelKind::ghs_ssa;
                const double excess = exact ? std::abs(albedo / r - 1) : std::max(0.0, albedo / r - 1);
                if (excess >= worst) {
                    worst = excess;
                    worst_theta = theta;
                }
                EXPECT_LT(excess, 5e-3) << c.label << " lambda " << lambda << " theta_i " << theta << " albedo " << albedo
                                        << " R " << r;
            }
        std::printf("%-46s worst %s %.2e (theta_i %.2f)\n", c.label.c_str(),
                    c.options.model == ModelKind::ghs || c.options.model == ModelKind::ghs_ssa ? "|albedo/R - 1|"
                                                                                               : "albedo/R - 1 > 0",
                    worst, worst_theta);
    }
}

// The library's albedo integrator (bsdf/albedo.hpp) against the references of hemisphere_albedo.hpp. It was wrong for
// narrow lobes at grazing incidence (issue 26: 1231 for the first case below, 7.40 for GGX alpha 1e-4), and for exact
// GHS on KC(3 um, 0.3 um, gamma 1.2) it reported 1.00075 at 60 deg and 1.0148 at 75 deg where the BRDF's integral was
// 0.9944 and 1.0016: K came from the same inaccurate rule. K now comes from the new one, so the GHS values of the
// issue no longer hold: the GHS rows check the documented bound |albedo - R| < 2e-3 (GhsEnergyOverGammaAndIncidence).
namespace {

struct AlbedoCase {
    std::string label;
    ModelOptions options;
    double theta_i_deg;
    double lambda_nm = 550.0;
};

ModelOptions two_scale(double sigma, double length, double gamma, double n, const char* material = "perfect") {
    auto o = test::kc_options(ModelKind::two_scale, sigma, length, gamma);
    o.cutoff_wavelengths = n;
    o.material = material;
    return o;
}
ModelOptions ggx(double alpha) {
    ModelOptions o;
    o.model = ModelKind::ggx;
    o.alpha_from = AlphaFrom::none;
    o.alpha = alpha;
    return o;
}

// |library - reference| and the library's error estimate, both below 1e-4; returns the difference.
double check_against_reference(const AlbedoCase& c, double reference) {
    const auto bsdf = make_bsdf(c.options);
    const DirectionalAlbedo a = directional_albedo(*bsdf, c.theta_i_deg * kDegree, c.lambda_nm);
    const double difference = a.total() - reference;
    EXPECT_LT(std::abs(difference), 1e-4) << c.label << " theta_i " << c.theta_i_deg << ": library " << a.total()
                                          << " reference " << reference;
    EXPECT_LT(a.error, 1e-4) << c.label << " theta_i " << c.theta_i_deg;
    std::printf("%-44s theta_i %6.2f  albedo %.9f  reference %.9f  diff %+.1e  estimate %.1e  evals %ld\n",
                c.label.c_str(), c.theta_i_deg, a.total(), reference, difference, a.error, a.evaluations);
    std::fflush(stdout);
    return difference;
}

}  // namespace

TEST(Albedo, IssueCasesMatchNestedQuadrature) {
    auto ghs_rough = test::kc_options(ModelKind::ghs, 3.0, 0.3, 1.2);
    // The value each case should have (issue 26, by integrating `brdf eval`; 0: GHS, R = 1 within 2e-3), and the
    // reference here.
    const std::vector<std::pair<AlbedoCase, double>> cases{
        {{"two_scale KC(0.001, 100, 6) N 100", two_scale(0.001, 100, 6, 100), 89.99}, 0.9988},
        {{"two_scale KC(0.02, 2, 3) N 150", two_scale(0.02, 2, 3, 150), 89.99}, 0.89},
        {{"ggx alpha 1e-4", ggx(1e-4), 89.99}, 0.905},
        {{"ghs KC(3, 0.3, 1.2)", ghs_rough, 60.0}, 0},
        {{"ghs KC(3, 0.3, 1.2)", ghs_rough, 75.0}, 0},
    };
    for (const auto& [c, issue] : cases) {
        const auto bsdf = make_bsdf(c.options);
        const double reference = test::hemisphere_albedo(*bsdf, c.theta_i_deg * kDegree, c.lambda_nm);
        if (issue > 0)
            EXPECT_NEAR(reference, issue, std::pow(10.0, -double(fmt::format("{}", issue).size() - 2))) << c.label;
        else
            EXPECT_NEAR(reference, 1.0, 2e-3) << c.label;
        check_against_reference(c, reference);
    }
}

TEST(Albedo, GgxMatchesItsSlopeSpaceIntegral) {
    double worst = 0;
    for (double alpha : {1e-4, 1e-3, 1e-2, 0.1, 0.3, 1.0})
        for (double theta : {0.0, 30.0, 60.0, 80.0, 85.0, 89.0, 89.9, 89.99})
            worst = std::max(worst, std::abs(check_against_reference({fmt::format("ggx alpha {}", alpha), ggx(alpha), theta},
                                                                     test::ggx_slope_albedo(alpha, theta * kDegree))));
    std::printf("GGX worst |library - slope integral| %.2e\n", worst);
}

TEST(Albedo, EveryModelMatchesNestedQuadrature) {
    std::vector<AlbedoCase> cases;
    for (double theta : {0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9, 89.99}) {
        cases.push_back({"ghs KC(0.001, 50, 4)", test::kc_options(ModelKind::ghs, 0.001, 50, 4), theta});
        cases.push_back({"ghs KC(2, 0.5, 1.5)", test::kc_options(ModelKind::ghs, 2, 0.5, 1.5), theta});
        cases.push_back({"ghs KC(0.5, 10, 2.5) Au 830 nm", test::kc_options(ModelKind::ghs, 0.5, 10, 2.5), theta, 830});
        cases.back().options.material = "Au";
        auto refit = test::kc_options(ModelKind::ghs, 0.05, 2, 3);
        refit.method = GhsMethod::refit;
        cases.push_back({"ghs refit KC(0.05, 2, 3)", refit, theta});
        cases.push_back({"ghs_ssa KC(0.02, 10, 3)", test::kc_options(ModelKind::ghs_ssa, 0.02, 10, 3), theta});
        auto link = test::kc_options(ModelKind::ggx, 0.1, 2, 3);
        link.alpha_from = AlphaFrom::kc_link;
        cases.push_back({"ggx kc_link L 2", link, theta});
        cases.push_back({"two_scale KC(0.15, 4, 4) N 50 Al", two_scale(0.15, 4, 4, 50, "Al"), theta});
        cases.push_back({"two_scale KC(0.5, 2, 1.5) N 20", two_scale(0.5, 2, 1.5, 20), theta, 360});
    }
    double worst = 0;
    for (const AlbedoCase& c : cases) {
        const auto bsdf = make_bsdf(c.options);
        worst = std::max(worst, std::abs(check_against_reference(
                                    c, test::hemisphere_albedo(*bsdf, c.theta_i_deg * kDegree, c.lambda_nm))));
    }
    std::printf("worst |library - nested quadrature| %.2e\n", worst);
}


// The GHS energy at extreme gamma (issue 26): K now comes from the same lobe-following cubature (the fixed rule before
// made KC(3 um, 0.3 um, gamma 1.2) carry 0.9944 at 60 deg), so what is left of |albedo - R| is the lookup of K:
// ln K is linear in lambda between wavelength nodes 2 % apart, and for the roughest fractal surfaces ln K bends enough
// in lambda for that to leave up to 1.8e-3 (measured 1.75e-3 at 75 deg, 549 nm, near the middle of a node interval).
// The bound documented in docs/MODELS.md is this test's.
TEST(Albedo, GhsEnergyOverGammaAndIncidence) {
    double worst = 0;
    for (const auto& [sigma, length] : {std::pair{3.0, 0.3}, std::pair{0.5, 2.0}})
        for (double gamma : {1.2, 1.5, 2.0, 3.0, 4.0}) {
            const auto bsdf = make_bsdf(test::kc_options(ModelKind::ghs, sigma, length, gamma));
            for (double lambda : {549.0, 550.0})
                for (double theta : {0.0, 30.0, 60.0, 75.0, 85.0, 89.0, 89.9}) {
                    const DirectionalAlbedo a = directional_albedo(*bsdf, theta * kDegree, lambda);
                    const double excess = std::abs(a.total() - 1.0);
                    worst = std::max(worst, excess);
                    EXPECT_LT(excess, 2e-3) << "KC(" << sigma << ", " << length << ", " << gamma << ") " << lambda
                                            << " nm theta_i " << theta << ": " << a.total();
                    std::printf("ghs KC(%g, %g, %g) %g nm theta_i %5.1f albedo - 1 %+.2e\n", sigma, length, gamma,
                                lambda, theta, a.total() - 1.0);
                }
        }
    std::printf("GHS worst |albedo - R| %.2e\n", worst);
}
