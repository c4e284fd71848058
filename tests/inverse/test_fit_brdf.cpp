// fit_brdf against data the fitted models did not make: the Kirchhoff BRDF (reference/kirchhoff_map) of synthesised KC
// maps of known statistics and `reference exact-1d`'s statistical mode, with 3 % multiplicative Gaussian noise: the
// rough map's sigma and L, the smooth case's PSD against Rayleigh-Rice, 1-D profile data, a narrow range that cannot
// constrain gamma; bad data (docs/FIT.md "Accuracy").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/inverse/brdf_data.hpp"
#include "surfscatter/inverse/fit_brdf.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/exact_1d_statistics.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter;
using ss::inverse::BrdfData;
using ss::inverse::FitOptions;

namespace {

constexpr double kThetaI = 30.0;

struct MapSpec {
    double sigma, corr_length, gamma;
    std::size_t size;
    double spacing, subarea;
};

// One lattice direction of a Kirchhoff result, as the data selections see it.
struct Direction {
    double theta_i_deg, o_x, o_y, brdf, coherent;
    double diffuse_peak;  // the largest brdf - coherent beyond 4 lattice steps of specular, at this case
    double steps;         // lattice steps from the specular direction
    std::size_t subareas;
};

// The ratio of the Kirchhoff reference's first-order geometric factor |i + o|^4 / (4 cos i cos o) (Beckmann's form,
// reference/kirchhoff_map.hpp) to the models' (cos i + cos o)^2 (GHS's g; Rayleigh-Rice's 4 cos i cos o differs from
// it the other way): 1 at specular, growing as |i_xy + o_xy|^2 / (cos i + cos o)^2 and away from cos i = cos o. Where it
// exceeds 1 the reference's lobe at small g is wider than every model's with the same PSD.
double geometric_factor_ratio(double theta_i_deg, double o_x, double o_y) {
    const double ci = std::cos(theta_i_deg * ss::kDegree), co = std::sqrt(std::max(0.0, 1 - o_x * o_x - o_y * o_y));
    const double a = ci + co, b2 = std::pow(o_x + std::sin(theta_i_deg * ss::kDegree), 2) + o_y * o_y;
    return (a * a + b2) * (a * a + b2) / (4 * ci * co * a * a);
}

// The Kirchhoff BRDF of one synthesised map at each incidence (phi_i 0) and wavelength, the directions `keep` accepts,
// every k-th of them per case so that at most `per_case` remain, times (1 + 0.03 N(0, 1)).
template <typename Keep>
BrdfData kirchhoff_data(const MapSpec& m, const std::string& material, const std::vector<double>& theta_i_deg,
                        const std::vector<double>& wavelengths_nm, Keep keep, std::size_t per_case,
                        std::uint64_t seed) {
    const ss::surface::KCorrelation kc(m.sigma, m.corr_length, m.gamma);
    const auto map = ss::surface::synthesize_surface(kc, {m.size, m.size, m.spacing}, seed);
    const auto conductor = ss::material::Conductor::from_name(material);
    std::mt19937_64 rng(seed + 1);
    std::normal_distribution<double> noise(0.0, 0.03);
    BrdfData data;
    data.source = "kirchhoff";
    for (const double theta_i : theta_i_deg)
        for (const double lambda : wavelengths_nm) {
            ss::reference::KirchhoffOptions o;
            o.lambda_nm = lambda;
            o.theta_i_rad = theta_i * ss::kDegree;
            o.subarea_um = m.subarea;
            o.threads = 1;
            const auto r = ss::reference::kirchhoff_brdf(map, conductor, o);
            const double sx = std::sin(theta_i * ss::kDegree);
            std::vector<Direction> directions;
            double peak = 0;
            for (std::size_t d = 0; d < r.brdf.size(); ++d) {
                const double steps = std::hypot((r.o_x[d] + sx) / r.step_x, r.o_y[d] / r.step_y);
                directions.push_back({theta_i, r.o_x[d], r.o_y[d], r.brdf[d], r.coherent[d], 0, steps, r.subareas});
                if (steps >= 4) peak = std::max(peak, r.brdf[d] - r.coherent[d]);
            }
            std::vector<Direction> kept;
            for (Direction& d : directions) {
                d.diffuse_peak = peak;
                if (keep(d)) kept.push_back(d);
            }
            const std::size_t stride = std::max<std::size_t>(1, (kept.size() + per_case - 1) / per_case);
            for (std::size_t j = 0; j < kept.size(); j += stride) {
                const Direction& d = kept[j];
                data.wavelength_nm.push_back(lambda);
                data.theta_i_deg.push_back(theta_i);
                data.phi_i_deg.push_back(0.0);
                data.theta_o_deg.push_back(std::asin(std::min(1.0, std::hypot(d.o_x, d.o_y))) / ss::kDegree);
                data.phi_o_deg.push_back(std::atan2(d.o_y, d.o_x) / ss::kDegree);
                data.brdf.push_back(d.brdf * (1.0 + noise(rng)));
            }
        }
    return data;
}

// Measurement-like directions: the diffuse lobe (at least 1 % of its peak), beyond the coherent peak (4 lattice steps
// of specular, and a coherent part under twice its incoherent bias brdf / M), where the reference's geometric factor
// is within 4 % of the models' (geometric_factor_ratio).
bool measured_lobe(const Direction& d) {
    return d.steps >= 4 && d.brdf >= 0.01 * d.diffuse_peak &&
           d.coherent < 2 * d.brdf / static_cast<double>(d.subareas) &&
           geometric_factor_ratio(d.theta_i_deg, d.o_x, d.o_y) <= 1.04;
}

const ss::inverse::ParameterEstimate& parameter(const ss::inverse::ModelFit& fit, const std::string& name) {
    for (const auto& p : fit.parameters)
        if (p.name == name) return p;
    throw std::runtime_error("no parameter " + name);
}

// The GHS fit alone, with the default options.
ss::inverse::ModelFit ghs_fit(const BrdfData& data, const std::string& material) {
    FitOptions options;
    options.material = material;
    options.models = {ss::bsdf::ModelKind::ghs};
    return ss::inverse::fit_brdf(data, options).fits[0];
}

}  // namespace

// A narrow range: a smooth surface of L 0.1 um seen at 0.16 < |i_xy + o_xy| < 0.35 (zeta L 0.14 to 0.49), near the
// PSD's flat top, where ln P = ln(sigma^2 L^2 (gamma - 1) / pi) - gamma zeta^2 L^2 + ... holds two numbers for three
// parameters: gamma is reported unconstrained, without a standard error, and the combination left open is named.
TEST(FitBrdf, NarrowRangeLeavesGammaUnconstrained) {
    const MapSpec spec{0.002, 0.1, 2.5, 1024, 0.03, 15.36};
    const auto near = [](const Direction& d) {
        const double q = std::hypot(d.o_x + std::sin(kThetaI * ss::kDegree), d.o_y);
        return q > 0.16 && q < 0.35;
    };
    const BrdfData data = kirchhoff_data(spec, "perfect", {kThetaI}, {450, 550, 700}, near, 100000, 13);
    ASSERT_GT(data.size(), 10u);
    const auto fit = ghs_fit(data, "perfect");
    for (const auto& p : fit.parameters) std::printf("%s = %g (%s)\n", p.name.c_str(), p.value, p.note.c_str());
    for (const auto& d : fit.degenerate_directions) std::printf("degenerate: %s\n", d.c_str());
    EXPECT_FALSE(parameter(fit, "gamma").constrained);
    EXPECT_FALSE(parameter(fit, "gamma").standard_error.has_value());
    EXPECT_FALSE(fit.degenerate_directions.empty());
}

TEST(FitBrdf, BadRowsAreNamed) {
    const std::string header = "wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,phi_o_deg,brdf\n";
    const std::string good = "550,30,0,30,180,1.5\n550,30,0,35,180,0.5\n";
    const auto message = [&](const std::string& text) {
        try {
            ss::inverse::parse_brdf_csv(text, "m.csv");
        } catch (const ss::Error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message("wavelength_nm,theta_i_deg,phi_i_deg,theta_o_deg,brdf\n550,30,0,30,1\n").find("m.csv:1"),
              std::string::npos);
    EXPECT_NE(message(header + good + "550,30,0,40,180,-0.1\n").find("m.csv:4: brdf"), std::string::npos);
    EXPECT_NE(message(header + good + "550,30,0,40,180,nan\n").find("m.csv:4: brdf"), std::string::npos);
    EXPECT_NE(message(header + good + "550,30,0,95,180,0.1\n").find("m.csv:4: theta_o_deg"), std::string::npos);
    EXPECT_NE(message(header + "550,90,0,40,180,0.1\n" + good).find("m.csv:2: theta_i_deg"), std::string::npos);
    EXPECT_NE(message(header + "550,30,0,30,180,1\n550,30,0,30,180,1.1\n").find("one direction"), std::string::npos);
    EXPECT_NE(message(header + good + "550,30,0,40,180\n").find("m.csv:4"), std::string::npos);
    EXPECT_EQ(message(header + good), "no error");
    const BrdfData data = ss::inverse::parse_brdf_csv(header + good + "550,30,0,40,180,0.2\n", "m.csv");
    FitOptions options;
    options.fixed["gamma"] = 0.5;
    EXPECT_THROW(ss::inverse::fit_brdf(data, options), ss::Error);
    options.fixed = {{"lay_angle_deg", 10}};
    EXPECT_THROW(ss::inverse::fit_brdf(data, options), ss::Error);
    options.fixed = {{"roughness", 1}};
    EXPECT_THROW(ss::inverse::fit_brdf(data, options), ss::Error);
}

// The 1-D route: `reference exact-1d`'s statistical mode (24 random profiles, 48 um, beam 12 um, of a KC surface
// sigma 0.1 um, L 1 um, gamma 2.5; a perfect conductor, s polarisation) at theta_i 30 deg and 600, 1000, 1600 nm
// (g0 3.3, 1.2, 0.46), its incoherent part every 1 deg with 3 % noise and the reference's own standard error,
// fitted with the 1-D GHS, SSA and GGX (FitOptions::profile). The directions: beyond twice the beam's half-width of
// specular, at least 1 % of the peak, and where GHS's geometric factor (cos i + cos o)^2 is within 4 % of first-order
// perturbation theory's 4 cos i cos o (farther out, at grazing exit, the exact lobe falls below GHS's by up to 30 %
// and a free gamma follows it: with all directions to 80 deg, L came out 18 % long and gamma 2.26, chi2/dof 5.8).
// Measured: sigma 0.0995, L 1.034, gamma 2.37 +- 0.011 (chi2/dof 1.42), GHS the best; 9.5 CPU s.
TEST(FitBrdf, ProfileDataFromExact1d) {
    const double sigma = 0.1, corr_length = 1.0, gamma = 2.5, theta_i = 30.0;
    const ss::surface::KCorrelation kc(sigma, corr_length, gamma);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> noise(0.0, 0.03);
    BrdfData data;
    data.source = "exact-1d";
    for (const double lambda : {600.0, 1000.0, 1600.0}) {
        ss::reference::Exact1dOptions o;
        o.lambda_nm = lambda;
        o.theta_i_rad = theta_i * ss::kDegree;
        o.polarisation = ss::reference::Polarisation::s;
        o.beam_width_um = 12;
        ss::reference::StatisticalOptions st;
        st.length_um = 48;
        st.realizations = 24;
        st.seed = 5;
        st.threads = 1;
        const auto r = ss::reference::solve_exact_1d_statistics(kc, ss::material::Conductor::perfect(), o, st);
        const double peak = *std::max_element(r.incoherent.begin(), r.incoherent.end());
        for (std::size_t j = 0; j < r.theta_o_rad.size(); j += 10) {
            const double t = r.theta_o_rad[j];
            const double ci = std::cos(theta_i * ss::kDegree), co = std::cos(t);
            const double factor = 4 * ci * co / ((ci + co) * (ci + co));
            if (std::abs(t - theta_i * ss::kDegree) < 2 * r.beam_half_width_rad || factor < 0.96 ||
                r.incoherent[j] < 1e-2 * peak)
                continue;
            data.wavelength_nm.push_back(lambda);
            data.theta_i_deg.push_back(theta_i);
            data.phi_i_deg.push_back(0.0);
            data.theta_o_deg.push_back(std::abs(t) / ss::kDegree);
            data.phi_o_deg.push_back(t > 0 ? 180.0 : 0.0);
            data.brdf.push_back(r.incoherent[j] * (1.0 + noise(rng)));
            data.brdf_stderr.push_back(std::hypot(0.03 * r.incoherent[j], r.incoherent_stderr[j]));
        }
    }
    FitOptions options;
    options.material = "perfect";
    options.profile = ss::bsdf::ProfilePolarisation::s;
    options.models = {ss::bsdf::ModelKind::ghs, ss::bsdf::ModelKind::ghs_ssa, ss::bsdf::ModelKind::ggx};
    const auto result = ss::inverse::fit_brdf(data, options);
    for (const auto& fit : result.fits) {
        std::printf("%s: chi2/dof %.3f, %d models, %.1f CPU s\n", ss::bsdf::to_string(fit.model).c_str(), fit.misfit,
                    fit.evaluations, fit.cpu_seconds);
        for (const auto& p : fit.parameters)
            std::printf("  %s = %.4g +- %.3g %s\n", p.name.c_str(), p.value, p.standard_error.value_or(0), p.note.c_str());
    }
    std::printf("%zu rows; %s\n", data.size(), result.verdict.c_str());
    const auto& ghs = result.fits[0];
    EXPECT_NEAR(parameter(ghs, "sigma_um").value / sigma, 1.0, 0.05);
    EXPECT_NEAR(parameter(ghs, "corr_length_um").value / corr_length, 1.0, 0.10);
    EXPECT_EQ(result.best, 0u);
}

// The rough map (KC sigma 0.12 um, L 2 um, gamma 2.5, gold) measured as a campaign would, so that sigma and L are
// told apart: theta_i 0, 30 and 60 deg at 450, 1000 and 2000 nm, g0 from 11.2 (0 deg, 450 nm) down to 0.5 (60 deg,
// 1000 nm). At 30 deg and 450-700 nm alone (g0 3.5-8.4) the lobe is nearly geometric and fixes a combination of sigma
// and L only (docs/FIT.md); the partly coherent lobes of smaller g0 follow g, hence sigma itself. The map: 2048^2 at
// 0.25 um, 32 um sub-areas (256: 6 % scatter per direction; the lattice step 0.014-0.06, below the lobe's width);
// the directions of measured_lobe, 200 per case at most: 832 rows, most of them at 450 and 1000 nm (at 2000 nm the
// lobe lies where the reference's geometric factor departs from GHS's). Measured: sigma 0.1161 +- 0.0014, L 2.085
// +- 0.083, gamma 2.30 +- 0.02 (8 % low: GHS's renormalisation, which the reference lacks, docs/FIT.md), relative rms
// 0.067, 20.8 CPU s (the data 6.5, the fit 13.3, at load 19); with the geometric factor within 10 %, L 2.37 and gamma 2.26; with every direction, sigma 0.097, L 1.11 and
// a misfit 0.16 from the far directions at 2000 nm, where the Beckmann form exceeds the models 3-fold.
TEST(FitBrdf, RoughMapRecoversSigmaAndL) {
    const MapSpec spec{0.12, 2.0, 2.5, 2048, 0.25, 32};
    const BrdfData data = kirchhoff_data(spec, "Au", {0, 30, 60}, {450, 1000, 2000}, measured_lobe, 200, 7);
    ASSERT_GT(data.size(), 500u);
    FitOptions options;
    options.material = "Au";
    options.models = {ss::bsdf::ModelKind::ghs, ss::bsdf::ModelKind::ggx};
    const auto result = ss::inverse::fit_brdf(data, options);
    for (const auto& fit : result.fits) {
        std::printf("%s: relative rms %.3f, %d models, %.1f CPU s\n", ss::bsdf::to_string(fit.model).c_str(),
                    fit.misfit, fit.evaluations, fit.cpu_seconds);
        for (const auto& p : fit.parameters)
            std::printf("  %s = %.4g +- %.3g %s\n", p.name.c_str(), p.value, p.standard_error.value_or(0), p.note.c_str());
    }
    std::printf("%zu rows; %s\n", data.size(), result.verdict.c_str());
    const auto& ghs = result.fits[0];
    EXPECT_NEAR(parameter(ghs, "sigma_um").value / spec.sigma, 1.0, 0.05);
    EXPECT_NEAR(parameter(ghs, "corr_length_um").value / spec.corr_length, 1.0, 0.10);
    EXPECT_TRUE(parameter(ghs, "sigma_um").constrained);
    EXPECT_TRUE(parameter(ghs, "corr_length_um").constrained);
    // The misfit is the data's own scatter (3 % noise and the reference's 6 %), and GHS fits best.
    EXPECT_LT(ghs.misfit, 0.09);
    EXPECT_EQ(result.best, 0u);
}

// The smooth case (g0 < 0.02): KC sigma 0.005 um, L 0.5 um, gamma 2.5 on a perfect conductor, theta_i 30 deg,
// 450, 550, 700 nm; the fitted GHS's PSD against the Rayleigh-Rice inversion of the data, P = f / (4 k^4 cos i cos o)
// (Q = 1: a perfect conductor), over the directions of measured_lobe, where the three geometric factors (the
// reference's, GHS's, Rayleigh-Rice's) agree within 4 %. The tolerance on the median ratio: those 4 % plus three
// standard errors of a median of N values with the per-direction scatter s = sqrt(1 / M + 0.03^2) (M sub-areas),
// 1.25 s / sqrt(N / 4) (neighbouring lattice directions are correlated through the window, ~4 per independent one).
TEST(FitBrdf, SmoothCaseMatchesRayleighRice) {
    const MapSpec spec{0.005, 0.5, 2.5, 2048, 0.0625, 16};
    const BrdfData data = kirchhoff_data(spec, "perfect", {kThetaI}, {450, 550, 700}, measured_lobe, 400, 11);
    ASSERT_GT(data.size(), 200u);
    const auto fit = ghs_fit(data, "perfect");
    const ss::surface::KCorrelation fitted(parameter(fit, "sigma_um").value, parameter(fit, "corr_length_um").value,
                                           parameter(fit, "gamma").value);
    std::vector<double> ratio;
    for (std::size_t j = 0; j < data.size(); ++j) {
        const double k = 2 * ss::kPi / (data.wavelength_nm[j] * 1e-3);
        const double ti = data.theta_i_deg[j] * ss::kDegree, to = data.theta_o_deg[j] * ss::kDegree;
        const double po = data.phi_o_deg[j] * ss::kDegree;
        const double zeta = k * std::hypot(std::sin(ti) + std::sin(to) * std::cos(po), std::sin(to) * std::sin(po));
        const double rayleigh_rice = data.brdf[j] / (4 * std::pow(k, 4) * std::cos(ti) * std::cos(to));
        ratio.push_back(fitted.psd(zeta) / rayleigh_rice);
    }
    std::sort(ratio.begin(), ratio.end());
    const double n = static_cast<double>(ratio.size());
    const double median = ratio[ratio.size() / 2];
    const double scatter = std::sqrt(1.0 / 64 + 0.03 * 0.03);
    const double tolerance = 0.04 + 3 * 1.25 * scatter / std::sqrt(n / 4);
    std::printf("sigma %.4g L %.4g gamma %.4g misfit %.3f; PSD / Rayleigh-Rice over %zu directions: median %.3f "
                "(tolerance %.3f), 10-90 %% %.3f-%.3f\n",
                parameter(fit, "sigma_um").value, parameter(fit, "corr_length_um").value,
                parameter(fit, "gamma").value, fit.misfit, ratio.size(), median, tolerance,
                ratio[ratio.size() / 10], ratio[ratio.size() * 9 / 10]);
    EXPECT_NEAR(median, 1.0, tolerance);
}
