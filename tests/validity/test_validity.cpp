// The comparison statistics, the binning, the verdict logic and one real end-to-end run (docs/VALIDITY.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "surfscatter/bsdf/profile_lobes.hpp"
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

// A model compared (compare_curves) on `deviation.size()` bins where the reference is 1 with relative standard error
// `eps` and the model is 1 + deviation[j]; `own` its stated accuracy.
sv::ModelResult compared(const char* name, const std::vector<double>& deviation, double eps, double own = 0) {
    const auto theta = grid(static_cast<int>(deviation.size()));
    std::vector<double> reference(deviation.size(), 1.0), stderr_(deviation.size(), eps), model;
    for (const double d : deviation) model.push_back(1.0 + d);
    sv::ModelResult m;
    m.model = name;
    m.comparison = sv::compare_curves(theta, reference, stderr_, model, sv::Criteria{});
    m.own_rel_uncertainty = own;
    return m;
}

// n bins alternating between a - b and a + b (median error a when b < a).
std::vector<double> around(double a, double b = 0, int n = 20) {
    std::vector<double> d;
    for (int j = 0; j < n; ++j) d.push_back(j % 2 ? a + b : a - b);
    return d;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
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

// Bins within the beam's angular spread of specular are left out of the comparison but count for the peak: the
// spread 4 / (k g cos theta_i), here 5.7 deg at 30 deg incidence, 550 nm, g 4 um, plus half a 3 deg bin.
TEST(Validity, NearSpecularBinsAreLeftOut) {
    const double k = 2 * ss::kPi / 0.55, g = 4, theta_i = 30 * ss::kDegree, bin = 3 * ss::kDegree;
    surfscatter::reference::StatisticalResult beam;
    beam.beam_half_width_rad = 2 / (k * g * std::cos(theta_i));  // as the reference reports it
    const double half = sv::near_specular_half_width_rad(beam);
    EXPECT_NEAR(half, 4 / (k * g * std::cos(theta_i)), 1e-15);
    const auto theta = grid(1801);
    std::vector<double> reference, stderr_, model;
    for (const double t : theta) {
        reference.push_back(std::abs(t - theta_i) < 0.05 ? 100.0 : 1.0);  // a spike at specular: the peak
        stderr_.push_back(0.01 * reference.back());
        model.push_back(std::abs(t - theta_i) < 0.09 ? 5.0 : 1.0);  // wrong within the spread (0.1 rad) only
    }
    auto b = sv::bin_curves(theta, reference, stderr_, {model}, bin, k, g);
    sv::mark_near_specular(b, theta_i, half, bin);
    std::size_t expected = 0;
    for (std::size_t i = 0; i < b.theta_o_rad.size(); ++i) {
        const bool near = std::abs(b.theta_o_rad[i] - theta_i) < half + bin / 2;
        expected += near;
        EXPECT_EQ(b.near_specular[i] != 0, near) << b.theta_o_rad[i];
    }
    EXPECT_EQ(b.near_specular_bins, expected);
    sv::Criteria criteria;
    criteria.peak_fraction = 0.005;  // the rest, 1 % of the spike's 100, is used
    const auto c = sv::compare_curves(b.theta_o_rad, b.reference, b.reference_stderr, b.models[0], criteria,
                                      b.near_specular);
    EXPECT_EQ(c.directions_used, b.theta_o_rad.size() - expected);
    EXPECT_NEAR(c.worst_rel_error, 0.0, 1e-12);  // the wrong bins all lie near specular
    criteria.peak_fraction = 0.02;  // the spike's bins, left out, still set the peak: 1 is under 2 % of it
    EXPECT_EQ(sv::compare_curves(b.theta_o_rad, b.reference, b.reference_stderr, b.models[0], criteria,
                                 b.near_specular).directions_used,
              0u);
}

// The uncertainties, against values written here: the reference moved by +-eps of its value moves |m / r - 1|; two
// models on the same side of the reference, beyond its error, move together; on opposite sides, apart; close to it
// on the same side, a move can carry the reference past one of them.
TEST(Validity, UncertaintiesOfErrorsAndLeads) {
    const auto moved = [](double m, double delta) { return std::abs(m / (1 + delta) - 1); };
    const auto worst = [](double now, double up, double down) {
        return std::max(std::abs(up - now), std::abs(down - now));
    };
    const double eps = 0.02;
    const auto ghs = compared("ghs", around(0.03), eps);
    EXPECT_NEAR(sv::error_uncertainty(ghs), worst(0.03, moved(1.03, eps), moved(1.03, -eps)), 1e-12);
    EXPECT_NEAR(sv::error_uncertainty(ghs), 0.021, 1e-3);
    // 30 and 50 % above: the lead 20 points, uncertain by 0.2 x 2 %.
    const auto high = compared("a", around(0.3), eps), higher = compared("b", around(0.5), eps);
    EXPECT_NEAR(sv::lead_uncertainty(high, higher),
                worst(0.2, moved(1.5, eps) - moved(1.3, eps), moved(1.5, -eps) - moved(1.3, -eps)), 1e-12);
    EXPECT_LT(sv::lead_uncertainty(high, higher), 0.005);
    // 3 % above and 4 % below: the lead 1 point, uncertain by about 2 x 2 %.
    const auto below = compared("kirchhoff", around(-0.04), eps);
    EXPECT_NEAR(sv::lead_uncertainty(ghs, below),
                worst(0.01, moved(0.96, eps) - moved(1.03, eps), moved(0.96, -eps) - moved(1.03, -eps)), 1e-12);
    EXPECT_GT(sv::lead_uncertainty(ghs, below), 0.035);
    // 2.6 and 5 % above a reference known to 4.5 %: moved up by 4.5 %, the second is the closer.
    const auto near_a = compared("a", around(0.026), 0.045), near_b = compared("b", around(0.05), 0.045);
    EXPECT_GT(sv::lead_uncertainty(near_a, near_b), 0.024);
    // The models' own accuracy in quadrature.
    const auto own = compared("ghs", around(0.03), eps, 3e-3);
    EXPECT_NEAR(sv::error_uncertainty(own), std::hypot(sv::error_uncertainty(ghs), 3e-3), 1e-12);
    EXPECT_NEAR(sv::lead_uncertainty(own, higher), std::hypot(sv::lead_uncertainty(ghs, higher), 3e-3), 1e-12);
    EXPECT_THROW(sv::lead_uncertainty(ghs, compared("x", around(0.03, 0, 10), eps)), ss::Error);
}

// Trusted: within tolerance and ahead of the next model beyond their combined uncertainty.
TEST(Validity, VerdictTrustsAClearLeader) {
    const auto v = sv::decide({compared("ghs", around(0.03, 0.01), 0.01), compared("ghs_ssa", around(0.08), 0.01),
                               compared("kirchhoff", around(0.30), 0.01)},
                              sv::Criteria{});
    EXPECT_TRUE(v.conclusive);
    EXPECT_TRUE(v.trusted) << v.text;
    EXPECT_EQ(v.best_model, "ghs");
    EXPECT_EQ(v.indistinguishable, (std::vector<std::string>{"ghs"}));
    EXPECT_EQ(v.within_tolerance, (std::vector<std::string>{"ghs", "ghs_ssa"}));
    EXPECT_EQ(v.ruled_out, (std::vector<std::string>{"kirchhoff"}));  // 30 % > 10 % + 2 x 1.3 %
    EXPECT_EQ(v.text.rfind("trust ghs (median error 3 %", 0), 0u) << v.text;
    EXPECT_NE(v.text.find("points ahead of ghs_ssa"), std::string::npos) << v.text;
}

// Medians 1 point apart: indistinguishable when the models straddle a reference known to 2 % (the lead's
// uncertainty about 4 points), a clear lead when both lie above it beyond its error (the reference's noise being
// common to both).
TEST(Validity, VerdictNamesIndistinguishableModels) {
    auto v = sv::decide({compared("ghs", around(0.03), 0.02), compared("ghs_ssa", around(-0.04), 0.02),
                         compared("kirchhoff", around(0.5), 0.02)},
                        sv::Criteria{});
    EXPECT_TRUE(v.conclusive);
    EXPECT_FALSE(v.trusted) << v.text;
    EXPECT_EQ(v.best_model, "ghs");
    EXPECT_EQ(v.indistinguishable, (std::vector<std::string>{"ghs", "ghs_ssa"}));
    EXPECT_EQ(v.ruled_out, (std::vector<std::string>{"kirchhoff"}));
    EXPECT_EQ(v.text.rfind("no single model can be trusted: ghs (", 0), 0u) << v.text;
    EXPECT_NE(v.text.find("and ghs_ssa (4 %) are indistinguishable"), std::string::npos) << v.text;
    v = sv::decide({compared("ghs", around(0.03), 0.02), compared("ghs_ssa", around(0.05), 0.02)}, sv::Criteria{});
    EXPECT_TRUE(v.trusted) << v.text;
    // The models' own accuracy enters: 0.5 points apart on the same side, with 4e-3 each, is not a lead.
    v = sv::decide({compared("ghs", around(0.03), 0.01, 4e-3), compared("ghs_ssa", around(0.035), 0.01, 4e-3)},
                   sv::Criteria{});
    EXPECT_FALSE(v.trusted) << v.text;
    EXPECT_TRUE(has(v.indistinguishable, "ghs_ssa"));
    v = sv::decide({compared("ghs", around(0.03), 0.01), compared("ghs_ssa", around(0.045), 0.01)}, sv::Criteria{});
    EXPECT_TRUE(v.trusted) << v.text;
}

// A lead beyond the uncertainty but below a tenth of the tolerance (kUsefulLead) is no reason to prefer a model:
// 0.5 points on the same side of a reference known to 0.1 % is certain, and still the two are named together.
TEST(Validity, VerdictWantsALeadWorthActingOn) {
    const auto ghs = compared("ghs", around(0.03), 0.001), ssa = compared("ghs_ssa", around(0.035), 0.001);
    EXPECT_LT(sv::lead_uncertainty(ghs, ssa), 0.005);
    auto v = sv::decide({ghs, ssa}, sv::Criteria{});
    EXPECT_FALSE(v.trusted) << v.text;
    EXPECT_EQ(v.indistinguishable, (std::vector<std::string>{"ghs", "ghs_ssa"}));
    EXPECT_NE(v.text.find("a useful lead at least 1"), std::string::npos) << v.text;
    sv::Criteria loose;
    loose.tolerance = 0.04;  // a useful lead is then 0.4 points: 0.5 is one
    v = sv::decide({ghs, ssa}, loose);
    EXPECT_TRUE(v.trusted) << v.text;
    EXPECT_NE(v.text.find("beyond their uncertainty of"), std::string::npos) << v.text;
}

TEST(Validity, VerdictWhenNoModelIsWithinTolerance) {
    const auto v = sv::decide({compared("ghs", around(0.25), 0.02), compared("kirchhoff", around(0.14), 0.02)},
                              sv::Criteria{});
    EXPECT_TRUE(v.conclusive);
    EXPECT_FALSE(v.trusted);
    EXPECT_EQ(v.best_model, "kirchhoff");
    EXPECT_TRUE(v.within_tolerance.empty());
    EXPECT_EQ(v.ruled_out, (std::vector<std::string>{"ghs"}));  // 25 % > 10 % + 2 x 2.5 %; 14 % < 10 % + 2 x 2.28 %
    EXPECT_EQ(v.text.rfind("no model is within the tolerance 10 %: the closest is kirchhoff", 0), 0u) << v.text;
}

// The reference outside its validity (its error above the tolerance, no usable direction, or a reason the route
// gives): nothing concluded, nothing ruled out, and the verdict says why.
TEST(Validity, VerdictAgainstAReferenceOutsideItsValidityRulesNothingOut) {
    auto v = sv::decide({compared("ghs", around(0.01), 0.15), compared("ghs_ssa", around(0.9), 0.15)}, sv::Criteria{});
    EXPECT_FALSE(v.conclusive);
    EXPECT_FALSE(v.trusted);
    EXPECT_TRUE(v.best_model.empty());
    EXPECT_TRUE(v.ruled_out.empty()) << v.text;
    EXPECT_NE(v.reference_problem.find("median standard error 15 % exceeds the tolerance 10 %"), std::string::npos);
    EXPECT_EQ(v.text.rfind("nothing can be concluded and no model is ruled out: the reference is outside its validity",
                           0),
              0u)
        << v.text;
    v = sv::decide({compared("ghs", around(0.01), 0.01), compared("ghs_ssa", around(0.9), 0.01)}, sv::Criteria{},
                   "sub-areas too small");
    EXPECT_FALSE(v.conclusive);
    EXPECT_TRUE(v.ruled_out.empty());
    EXPECT_NE(v.text.find("(sub-areas too small)"), std::string::npos) << v.text;
    sv::ModelResult none;
    none.model = "ghs";
    v = sv::decide({none}, sv::Criteria{});
    EXPECT_FALSE(v.conclusive);
    EXPECT_NE(v.reference_problem.find("no direction has a reference"), std::string::npos) << v.reference_problem;
}

// A smooth KC profile (k sigma = 0.11) at 60 deg: GHS and SSA agree with the exact solution, Kirchhoff (no
// Rayleigh-Rice polarisation factor, tangent-plane obliquity) does not at such a wide angle. ~5 CPU s.
TEST(Validity, SmoothProfileTrustsGhsAndSsaNotKirchhoffAtWideAngles) {
    const ss::surface::KCorrelation surface(0.01, 1.0, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(60);
    study.criteria.tolerance = 0.2;  // 64 profiles leave the reference about 9 % noise: 10 % cannot be shown
    const auto cases = sv::profile_validity(surface, conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    const auto& c = cases.front();
    ASSERT_TRUE(c.verdict.conclusive) << c.verdict.text;
    const auto& within = c.verdict.within_tolerance;
    EXPECT_NE(std::find(within.begin(), within.end(), "ghs"), within.end()) << c.verdict.text;
    EXPECT_NE(std::find(within.begin(), within.end(), "ghs_ssa"), within.end()) << c.verdict.text;
    EXPECT_EQ(std::find(within.begin(), within.end(), "kirchhoff"), within.end()) << c.verdict.text;
    EXPECT_NE(std::find(within.begin(), within.end(), "two_scale"), within.end()) << c.verdict.text;
    ASSERT_EQ(c.models.size(), 4u);  // ghs, ghs_ssa, kirchhoff, two_scale; gamma 3: no ggx_stats
    EXPECT_EQ(c.models[3].model, "two_scale");
    ASSERT_EQ(c.not_compared.size(), 1u);
    EXPECT_EQ(c.not_compared.front().rfind("ggx_stats: ", 0), 0u) << c.not_compared.front();
    EXPECT_GT(c.models[2].comparison.median_rel_error, 2 * c.models[0].comparison.median_rel_error);
    // A perfect conductor: every model and the reference conserve energy.
    EXPECT_NEAR(c.reference_energy, 1.0, 2e-3);
    for (const auto& m : c.models) EXPECT_NEAR(m.model_energy, 1.0, 2e-3) << m.model;
}

// The beam's kernel (docs/VALIDITY.md "The beam's kernel") on a lobe whose closed-form average is known: a Gaussian
// of standard deviation s in q - K (q = k sin theta_o, K = k sin theta), over cos theta, so that the kernel's weight
// cos theta(K) cancels its 1 / cos theta. Averaged over K ~ N(k sin theta_i, 1/g) it becomes the convolution of the two
// Gaussians, s / sqrt(s^2 + 1/g^2) exp(-(q - k sin theta_i)^2 / (2 (s^2 + 1/g^2))), over the kernel's mean of
// cos theta(K), cos theta_i - 1 / (2 g^2 k^2 cos^3 theta_i) to O((k g)^-4). s = 1/g (a lobe as narrow as the
// kernel: the average doubles its variance and halves its peak over sqrt 2) needs more nodes than s = 4/g.
TEST(Validity, BeamKernelOnAGaussianLobeIsTheConvolutionOfTwoGaussians) {
    const double lambda = 550, g = 6, k = 2 * ss::kPi / (lambda * 1e-3), sigma = 1 / g;
    const auto theta_o = ss::bsdf::uniform_theta_grid(1800);
    for (const double theta_i_deg : {0.0, 40.0})
        for (const double s : {sigma, 4 * sigma}) {
            const double theta_i = theta_i_deg * ss::kDegree, k0 = k * std::sin(theta_i);
            int calls = 0;
            const sv::LobeAtIncidence lobe = [&](double theta, const std::vector<double>& directions) {
                ++calls;
                std::vector<double> out;
                for (const double t : directions)
                    out.push_back(std::exp(-std::pow(k * std::sin(t) - k * std::sin(theta), 2) / (2 * s * s)) /
                                  std::cos(theta));
                return out;
            };
            const std::vector<double> nominal = lobe(theta_i, theta_o);
            calls = 0;
            const sv::BlurredLobe b = sv::beam_blurred(lobe, nominal, theta_o, k, theta_i, g);
            const double c = std::cos(theta_i), mean_cos = c - 1 / (2 * g * g * k * k * c * c * c);
            const double var = s * s + sigma * sigma;
            double worst = 0, peak_ratio = 0;
            for (std::size_t j = 0; j < theta_o.size(); ++j) {
                const double d = k * std::sin(theta_o[j]) - k0;
                const double expected = s / std::sqrt(var) * std::exp(-d * d / (2 * var)) / mean_cos;
                if (expected < 0.01 * s / std::sqrt(var) / mean_cos) continue;
                worst = std::max(worst, std::abs(b.intensity_per_rad[j] / expected - 1));
                if (std::abs(d) < 1e-9) peak_ratio = b.intensity_per_rad[j] / nominal[j];
            }
            std::printf("[ measured ] theta_i %g deg, s = %g/g: %d nodes, rule error %.2g, worst |blurred / closed "
                        "form - 1| %.2g\n",
                        theta_i_deg, s * g, b.nodes, b.rule_error, worst);
            EXPECT_LE(worst, 2e-3) << "theta_i " << theta_i_deg << ", s " << s;
            EXPECT_LE(b.rule_error, sv::kBlurRuleTolerance);
            EXPECT_GE(calls, b.nodes - 1);  // the middle node is the nominal curve
            if (s == sigma) {
                EXPECT_GT(b.nodes, 3);
                if (theta_i_deg == 0) {
                    EXPECT_NEAR(peak_ratio, 1 / std::sqrt(2.0), 2e-3);
                }
            }
        }
    // Only the directions asked for are averaged (to the side lobes' interpolation tolerance: whether they are
    // interpolated is decided on each set of directions); the others keep the nominal value.
    std::vector<char> needed(theta_o.size(), 0);
    for (std::size_t j = 900; j < 950; ++j) needed[j] = 1;
    const sv::LobeAtIncidence narrow = [&](double theta, const std::vector<double>& directions) {
        std::vector<double> out;
        for (const double t : directions) out.push_back(std::exp(-std::pow(k * (std::sin(t) - std::sin(theta)) * g, 2) / 2));
        return out;
    };
    const auto nominal = narrow(0, theta_o);
    const sv::BlurredLobe part = sv::beam_blurred(narrow, nominal, theta_o, k, 0, g, needed);
    const sv::BlurredLobe all = sv::beam_blurred(narrow, nominal, theta_o, k, 0, g);
    for (std::size_t j = 0; j < theta_o.size(); ++j)
        if (needed[j]) {
            EXPECT_NEAR(part.intensity_per_rad[j] / all.intensity_per_rad[j], 1.0, 4e-4) << j;
        } else {
            EXPECT_DOUBLE_EQ(part.intensity_per_rad[j], nominal[j]) << j;
        }
    EXPECT_THROW(sv::beam_blurred(narrow, nominal, theta_o, k, 0, -1), ss::Error);
    EXPECT_THROW(sv::beam_blurred(narrow, {1.0}, theta_o, k, 0, g), ss::Error);
}

// The side incidences' lobes are computed on a subset of the directions and interpolated (their factor over the
// shifted nominal curve): a lobe whose shape changes with the incidence other than through k sin theta_o - K (and, as
// the profiles' statistics, mirror-symmetric: I(-theta, theta_o) = I(theta, -theta_o)), against
// the kernel's integral by a 4001-point trapezoid in K written here, at 0, 30 and 60 deg.
TEST(Validity, BeamKernelWithInterpolatedSideLobesMatchesDirectQuadrature) {
    const double lambda = 550, g = 8, k = 2 * ss::kPi / (lambda * 1e-3), s = 3 / g;
    const auto theta_o = ss::bsdf::uniform_theta_grid(1800);
    const auto shape = [&](double theta, double t) {
        return std::exp(-std::pow(k * (std::sin(t) - std::sin(theta)), 2) / (2 * s * s)) * std::cos(t) *
               (1 + 2 * std::sin(t) * std::sin(theta)) / std::cos(theta);
    };
    for (const double theta_i_deg : {0.0, 30.0, 60.0}) {
        const double theta_i = theta_i_deg * ss::kDegree, k0 = k * std::sin(theta_i);
        std::size_t evaluated = 0;
        const sv::LobeAtIncidence lobe = [&](double theta, const std::vector<double>& directions) {
            evaluated += directions.size();
            std::vector<double> out;
            for (const double t : directions) out.push_back(shape(theta, t));
            return out;
        };
        const std::vector<double> nominal = lobe(theta_i, theta_o);
        evaluated = 0;
        const sv::BlurredLobe b = sv::beam_blurred(lobe, nominal, theta_o, k, theta_i, g);
        double worst = 0, peak = 0;
        for (const double v : nominal) peak = std::max(peak, v);
        for (std::size_t j = 0; j < theta_o.size(); j += 7) {
            if (nominal[j] < 0.01 * peak || std::abs(theta_o[j] - theta_i) < 4 / (k * g * std::cos(theta_i))) continue;
            // The plane waves K = k0 + u, weight cos theta(K) exp(-u^2 g^2 / 2), u within 8 / g.
            double sum = 0, total = 0;
            for (int m = -2000; m <= 2000; ++m) {
                const double u = m * 8.0 / (2000 * g), kx = k0 + u;
                if (!(std::abs(kx) < k)) continue;
                const double w = std::exp(-0.5 * u * u * g * g) * std::sqrt(1 - kx * kx / (k * k));
                const double theta = std::asin(kx / k);
                sum += w * (theta >= 0 ? shape(theta, theta_o[j]) : shape(-theta, -theta_o[j]));
                total += w;
            }
            worst = std::max(worst, std::abs(b.intensity_per_rad[j] / (sum / total) - 1));
        }
        std::printf("[ measured ] theta_i %g deg: %d nodes, worst |blurred / quadrature - 1| %.2g, %zu directions "
                    "evaluated for %d side incidences of 1801\n",
                    theta_i_deg, b.nodes, worst, evaluated, b.nodes - 1);
        EXPECT_LE(worst, 2e-3) << theta_i_deg;
        // At 60 deg the lobe reaches 82 deg, where the ratio of cos theta_o at the shifted directions curves within
        // the sparse grid's step: the side lobes are then evaluated everywhere.
        if (theta_i_deg < 45)
            EXPECT_LT(evaluated, static_cast<std::size_t>(b.nodes - 1) * 1801 / 4) << theta_i_deg;
        else
            EXPECT_EQ(evaluated, static_cast<std::size_t>(b.nodes - 1) * 1801) << theta_i_deg;
    }
}

// Issue 34 item 3's smooth surface (KC sigma 0.005 um, L 1.5 um, gamma 3; k sigma 0.057, where first-order
// perturbation theory is exact), a perfect conductor, s, 550 nm, normal incidence, 30 um profiles under a 6 um beam,
// 24 profiles: the models averaged over the reference's beam agree with exact-1d in every bin validity uses (3 deg,
// specular zone left out), to 2 % + 2 standard errors (measured 0.3-0.6 %); plane-wave, they fell up to 8 % short
// next to the specular zone. (At oblique incidence GHS and SSA differ from first-order theory in s by their own
// (cos i + cos o)^2 / (4 cos i cos o), 3.9 % at 40 / 58.5 deg: a model error, not the beam's.) ~8 CPU s.
TEST(Validity, BlurredModelsMatchTheReferenceOnTheSmoothSurface) {
    const ss::surface::KCorrelation surface(0.005, 1.5, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(0);
    study.beam_width_um = 6;
    study.statistical.length_um = 30;
    study.statistical.realizations = 24;
    study.criteria.bin_deg = 3;
    const auto cases = sv::profile_validity(surface, conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    const auto& c = cases.front();
    ASSERT_TRUE(c.verdict.conclusive) << c.verdict.text;
    for (std::size_t m = 0; m < c.models.size(); ++m) {
        const auto& model = c.models[m];
        if (model.model == "kirchhoff") continue;  // not first-order exact: (1 + cos o)^2 / (4 cos^2 o) off
        const auto& used = model.comparison.used;
        ASSERT_GE(used.size(), 6u) << model.model;
        double worst = 0;
        for (const std::size_t b : used) {
            const double r = c.binned.reference[b], e = c.binned.reference_stderr[b], v = c.binned.models[m][b];
            worst = std::max(worst, std::abs(v / r - 1));
            EXPECT_LE(std::abs(v - r), 0.02 * r + 2 * e)
                << model.model << ", bin " << c.binned.theta_o_rad[b] / ss::kDegree << " deg: model / reference "
                << v / r << ", relative standard error " << e / r;
        }
        EXPECT_GE(model.blur_nodes, 3) << model.model;
        std::printf("[ measured ] %s: %zu bins, worst |blurred model / reference - 1| %.4f, median %.4f, %d nodes\n",
                    model.model.c_str(), used.size(), worst, model.comparison.median_rel_error, model.blur_nodes);
    }
}

// Thorsos' L = 4 g runs, with the error the profile's ends leave estimated (a flat profile of that length against
// one twice as long); on a surface 10 times smoother (100 times less diffuse light) the same ends exceed the
// tolerance, and the reference is outside its validity there. ~3 CPU s.
TEST(Validity, ProfileOfFourBeamWidthsRunsWithItsEdgeErrorEstimated) {
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(0);
    study.statistical.length_um = 4 * study.beam_width_um;
    study.statistical.realizations = 8;
    auto cases = sv::profile_validity(ss::surface::KCorrelation(0.01, 1.0, 3.0), conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    EXPECT_GT(cases.front().edge_rel_error, 1e-4);
    EXPECT_LT(cases.front().edge_rel_error, 0.03);
    cases = sv::profile_validity(ss::surface::KCorrelation(0.001, 1.0, 3.0), conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    EXPECT_GT(cases.front().edge_rel_error, study.criteria.tolerance);
    EXPECT_FALSE(cases.front().verdict.conclusive);
    EXPECT_NE(cases.front().verdict.reference_problem.find("the profile's ends, 2 beam widths either side"),
              std::string::npos)
        << cases.front().verdict.text;
    // Under 2 beam widths: exact-1d refuses.
    study.statistical.length_um = 3.9 * study.beam_width_um;
    EXPECT_THROW(sv::profile_validity(ss::surface::KCorrelation(0.01, 1.0, 3.0), conductor, study), ss::Error);
}

// A target standard error: rounds of profiles (24 first, then at most as many again) until the reference's median relative
// standard error over the bins used reaches it; a cap below what it needs stops short and says so. ~3 CPU s.
TEST(Validity, TargetStandardErrorRunsProfilesUntilReached) {
    const ss::surface::KCorrelation surface(0.01, 1.0, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(0);
    study.target_rel_stderr = 0.12;
    study.statistical.realizations = 200;  // the cap
    auto cases = sv::profile_validity(surface, conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    EXPECT_TRUE(cases.front().target_reached);
    EXPECT_LE(cases.front().reference_rel_stderr, 0.12);
    const std::size_t n = cases.front().reference.realizations;
    EXPECT_GE(n, ss::reference::kMinControlledRealizations);  // the first round
    EXPECT_LE(n, 200u);
    study.target_rel_stderr = 0.01;
    study.statistical.realizations = 20;
    cases = sv::profile_validity(surface, conductor, study);
    ASSERT_EQ(cases.size(), 1u);
    EXPECT_FALSE(cases.front().target_reached);
    EXPECT_EQ(cases.front().reference.realizations, 20u);
    EXPECT_GT(cases.front().reference_rel_stderr, 0.01);
}

TEST(Validity, RefusesBadInput) {
    const ss::surface::KCorrelation surface(0.01, 1.0, 3.0);
    const auto conductor = ss::material::Conductor::from_name("perfect");
    auto study = smooth_study(90);
    EXPECT_THROW(sv::profile_validity(surface, conductor, study), ss::Error);
    study.theta_i_deg = {};
    EXPECT_THROW(sv::profile_validity(surface, conductor, study), ss::Error);
}
