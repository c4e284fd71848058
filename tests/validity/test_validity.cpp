// The comparison statistics, the binning, the verdict logic and one real end-to-end run (docs/VALIDITY.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/validity/validity.hpp"

namespace ss = surfscatter;
namespace sv = surfscatter::validity;

namespace {

std::vector<double> grid(int n) {
    std::vector<double> theta;
    for (int j = 0; j < n; ++j) theta.push_back(-ss::kPi / 2 + ss::kPi * j / (n - 1));
    return theta;
}

sv::ModelResult model_with(const char* name, double median, std::size_t used, double reference_stderr) {
    sv::ModelResult m;
    m.model = name;
    m.comparison.median_rel_error = median;
    m.comparison.worst_rel_error = 2 * median;
    m.comparison.directions_used = used;
    m.comparison.reference_median_rel_stderr = reference_stderr;
    return m;
}

// The worked example of docs/VALIDITY.md: a smooth KC profile, a perfect conductor, 550 nm, s, at `theta_i_deg`.
sv::ProfileStudy smooth_study(double theta_i_deg) {
    sv::ProfileStudy study;
    study.wavelengths_nm = {550};
    study.theta_i_deg = {theta_i_deg};
    study.polarisations = {ss::bsdf::ProfilePolarisation::s};
    study.beam_width_um = 4;
    study.statistical.length_um = 24;
    study.statistical.realizations = 64;
    study.statistical.seed = 1;
    study.criteria.bin_deg = 10;
    return study;
}

}  // namespace

TEST(Validity, CompareCurvesUsesTheDirectionsAboveOnePercentOfThePeak) {
    const auto theta = grid(181);
    std::vector<double> reference, stderr_, model;
    for (std::size_t j = 0; j < theta.size(); ++j) {
        reference.push_back(std::exp(-theta[j] * theta[j] / 0.1));  // a lobe, 1 % at |theta| = 0.68 rad
        model.push_back(reference.back() * (1.0 + 0.3 * std::sin(3.0 * theta[j])));
        // The far tails of the lobe's used part carry a standard error of half its value: excluded.
        stderr_.push_back(std::abs(theta[j]) > 0.6 ? 0.5 * reference.back() : 0.01 * reference.back());
    }
    sv::Criteria criteria;
    const auto c = sv::compare_curves(theta, reference, stderr_, model, criteria);

    // Written here: the errors at the directions above 1 % of the peak with a standard error within 25 %.
    std::vector<double> errors;
    std::size_t excluded = 0;
    double worst = 0, worst_theta = 0;
    for (std::size_t j = 0; j < theta.size(); ++j) {
        if (reference[j] < 0.01) continue;
        if (std::abs(theta[j]) > 0.6) {
            ++excluded;
            continue;
        }
        const double e = std::abs(model[j] - reference[j]) / reference[j];
        errors.push_back(e);
        if (e > worst) worst = e, worst_theta = theta[j];
    }
    std::sort(errors.begin(), errors.end());
    const std::size_t n = errors.size();
    const double median = n % 2 ? errors[n / 2] : 0.5 * (errors[n / 2 - 1] + errors[n / 2]);
    ASSERT_GT(excluded, 0u);
    EXPECT_EQ(c.directions_used, n);
    EXPECT_EQ(c.used.size(), n);
    EXPECT_EQ(c.directions_excluded, excluded);
    EXPECT_DOUBLE_EQ(c.median_rel_error, median);
    EXPECT_DOUBLE_EQ(c.worst_rel_error, worst);
    EXPECT_DOUBLE_EQ(c.worst_theta_o_rad, worst_theta);
    EXPECT_NEAR(c.reference_median_rel_stderr, 0.01, 1e-12);

    EXPECT_THROW(sv::compare_curves(theta, reference, stderr_, std::vector<double>(3, 1.0), criteria), ss::Error);
}

TEST(Validity, BinsAverageTheCurvesAndScaleTheStandardErrorBySpeckles) {
    const auto theta = grid(1801);
    std::vector<double> reference, stderr_, model;
    for (const double t : theta) {
        reference.push_back(2.0 + t);
        stderr_.push_back(0.1);
        model.push_back(3.0 * t);
    }
    const double bin = 5 * ss::kDegree, k = 2 * ss::kPi / 0.5, g = 10.0;
    const auto b = sv::bin_curves(theta, reference, stderr_, {model}, bin, k, g);
    ASSERT_EQ(b.theta_o_rad.size(), 36u);  // 180 / 5
    for (std::size_t i = 0; i < b.theta_o_rad.size(); ++i) {
        // Linear curves: each bin's mean is the curve at the bin's mean angle.
        EXPECT_NEAR(b.reference[i], 2.0 + b.theta_o_rad[i], 1e-12);
        EXPECT_NEAR(b.models[0][i], 3.0 * b.theta_o_rad[i], 1e-12);
        const double speckle = 2.0 / (k * g * std::max(std::cos(b.theta_o_rad[i]), 1e-3));
        EXPECT_NEAR(b.reference_stderr[i], 0.1 / std::sqrt(std::max(1.0, bin / speckle)), 1e-12);
    }
    const auto none = sv::bin_curves(theta, reference, stderr_, {model}, 0.0, k, g);
    EXPECT_EQ(none.reference, reference);
    EXPECT_EQ(none.theta_o_rad, theta);
}

TEST(Validity, VerdictsOnConstructedCases) {
    sv::Criteria criteria;  // tolerance 10 %
    // Trusted: the smallest median within tolerance + the reference's uncertainty (2 %); SSA within it too.
    auto v = sv::decide({model_with("ghs", 0.05, 20, 0.02), model_with("ghs_ssa", 0.11, 20, 0.02),
                         model_with("kirchhoff", 0.30, 20, 0.02)},
                        criteria);
    EXPECT_TRUE(v.conclusive);
    EXPECT_TRUE(v.trusted);
    EXPECT_EQ(v.best_model, "ghs");
    EXPECT_EQ(v.within_tolerance, (std::vector<std::string>{"ghs", "ghs_ssa"}));
    EXPECT_NE(v.text.find("trust ghs"), std::string::npos);
    EXPECT_EQ(v.ruled_out, (std::vector<std::string>{"kirchhoff"}));  // 30 % > 10 % + 2 x 2 %
    // No model close enough.
    v = sv::decide({model_with("ghs", 0.25, 20, 0.02), model_with("kirchhoff", 0.15, 20, 0.02)}, criteria);
    EXPECT_TRUE(v.conclusive);
    EXPECT_FALSE(v.trusted);
    EXPECT_EQ(v.best_model, "kirchhoff");
    EXPECT_TRUE(v.within_tolerance.empty());
    EXPECT_NE(v.text.find("no model"), std::string::npos);
    // The reference's own error larger than the tolerance: no model certified, but one far off is ruled out.
    v = sv::decide({model_with("ghs", 0.01, 20, 0.15), model_with("ghs_ssa", 0.41, 20, 0.15),
                    model_with("kirchhoff", 0.39, 20, 0.15)},
                   criteria);
    EXPECT_FALSE(v.conclusive);
    EXPECT_FALSE(v.trusted);
    EXPECT_TRUE(v.best_model.empty());
    EXPECT_EQ(v.ruled_out, (std::vector<std::string>{"ghs_ssa"}));  // 41 % > 10 % + 2 x 15 % > 39 %
    EXPECT_NE(v.text.find("no model can be certified"), std::string::npos) << v.text;
    // No usable direction: nothing concluded.
    v = sv::decide({model_with("ghs", 0.0, 0, 0.0)}, criteria);
    EXPECT_FALSE(v.conclusive);
    EXPECT_NE(v.text.find("nothing can be concluded"), std::string::npos);
}

// A smooth KC profile (k sigma = 0.11) at 60 deg: GHS and SSA agree with the exact solution, Kirchhoff (no
// Rayleigh-Rice polarisation factor, tangent-plane obliquity) does not at such a wide angle. ~5 CPU s.
TEST(Validity, SmoothProfileTrustsGhsAndSsaNotKirchhoffAtWideAngles) {
    const ss::surface::KCorrelation surface(0.01, 1.0, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    const auto cases = sv::profile_validity(surface, conductor, smooth_study(60));
    ASSERT_EQ(cases.size(), 1u);
    const auto& c = cases.front();
    ASSERT_TRUE(c.verdict.conclusive) << c.verdict.text;
    EXPECT_TRUE(c.verdict.trusted) << c.verdict.text;
    const auto& within = c.verdict.within_tolerance;
    EXPECT_NE(std::find(within.begin(), within.end(), "ghs"), within.end()) << c.verdict.text;
    EXPECT_NE(std::find(within.begin(), within.end(), "ghs_ssa"), within.end()) << c.verdict.text;
    EXPECT_EQ(std::find(within.begin(), within.end(), "kirchhoff"), within.end()) << c.verdict.text;
    ASSERT_EQ(c.models.size(), 3u);
    EXPECT_GT(c.models[2].comparison.median_rel_error, 2 * c.models[0].comparison.median_rel_error);
    // A perfect conductor: every model and the reference conserve energy.
    EXPECT_NEAR(c.reference_energy, 1.0, 2e-3);
    for (const auto& m : c.models) EXPECT_NEAR(m.model_energy, 1.0, 2e-3) << m.model;
}

TEST(Validity, RefusesBadInput) {
    const ss::surface::KCorrelation surface(0.01, 1.0, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(90);
    EXPECT_THROW(sv::profile_validity(surface, conductor, study), ss::Error);
    study.theta_i_deg = {};
    EXPECT_THROW(sv::profile_validity(surface, conductor, study), ss::Error);
}
