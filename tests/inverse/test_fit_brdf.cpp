// fit_brdf against data the fitted models did not make: the Kirchhoff BRDF (reference/kirchhoff_map) of a synthesised
// KC map of known statistics, at three wavelengths, with 3 % multiplicative Gaussian noise, over a narrow range that
// cannot constrain gamma; bad data. (The rough-map recovery and the smooth case against Rayleigh-Rice are not here yet:
// docs/FIT.md "Left to do".)
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
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace ss = surfscatter;
using ss::inverse::BrdfData;
using ss::inverse::FitOptions;

namespace {

constexpr double kThetaI = 30.0;
const std::vector<double> kWavelengths = {450.0, 550.0, 700.0};

struct MapSpec {
    double sigma, corr_length, gamma;
    std::size_t size;
    double spacing, subarea;
};

// The Kirchhoff BRDF of one synthesised map at the three wavelengths (theta_i 30 deg, phi_i 0, gold), the directions
// `keep` accepts (given o_x, o_y, brdf, peak, coherent part), every `stride`-th of them, times (1 + 0.03 N(0, 1)).
template <typename Keep>
BrdfData kirchhoff_data(const MapSpec& m, const std::string& material, Keep keep, std::size_t stride,
                        std::uint64_t seed) {
    const ss::surface::KCorrelation kc(m.sigma, m.corr_length, m.gamma);
    const auto map = ss::surface::synthesize_surface(kc, {m.size, m.size, m.spacing}, seed);
    const auto conductor = ss::material::Conductor::from_name(material);
    std::mt19937_64 rng(seed + 1);
    std::normal_distribution<double> noise(0.0, 0.03);
    BrdfData data;
    data.source = "kirchhoff";
    for (const double lambda : kWavelengths) {
        ss::reference::KirchhoffOptions o;
        o.lambda_nm = lambda;
        o.theta_i_rad = kThetaI * ss::kDegree;
        o.subarea_um = m.subarea;
        o.threads = 1;
        const auto r = ss::reference::kirchhoff_brdf(map, conductor, o);
        const double peak = *std::max_element(r.brdf.begin(), r.brdf.end());
        std::size_t kept = 0;
        for (std::size_t d = 0; d < r.brdf.size(); ++d) {
            if (!keep(r.o_x[d], r.o_y[d], r.brdf[d], peak, r.coherent[d]) || kept++ % stride != 0) continue;
            const double s = std::hypot(r.o_x[d], r.o_y[d]);
            data.wavelength_nm.push_back(lambda);
            data.theta_i_deg.push_back(kThetaI);
            data.phi_i_deg.push_back(0.0);
            data.theta_o_deg.push_back(std::asin(std::min(1.0, s)) / ss::kDegree);
            data.phi_o_deg.push_back(std::atan2(r.o_y[d], r.o_x[d]) / ss::kDegree);
            data.brdf.push_back(r.brdf[d] * (1.0 + noise(rng)));
        }
    }
    return data;
}

const ss::inverse::ParameterEstimate& parameter(const ss::inverse::ModelFit& fit, const std::string& name) {
    for (const auto& p : fit.parameters)
        if (p.name == name) return p;
    throw std::runtime_error("no parameter " + name);
}

}  // namespace

// A narrow range: a smooth surface of L 0.1 um seen at 0.16 < |i_xy + o_xy| < 0.35 (zeta L 0.14 to 0.49), near the
// PSD's flat top, where ln P = ln(sigma^2 L^2 (gamma - 1) / pi) - gamma zeta^2 L^2 + ... holds two numbers for three
// parameters: gamma is reported unconstrained, without a standard error, and the combination left open is named.
TEST(FitBrdf, NarrowRangeLeavesGammaUnconstrained) {
    const MapSpec spec{0.002, 0.1, 2.5, 1024, 0.03, 15.36};
    const auto near = [](double ox, double oy, double, double, double) {
        const double q = std::hypot(ox + std::sin(kThetaI * ss::kDegree), oy);
        return q > 0.16 && q < 0.35;
    };
    const BrdfData data = kirchhoff_data(spec, "perfect", near, 1, 13);
    ASSERT_GT(data.size(), 10u);
    FitOptions options;
    options.material = "perfect";
    options.models = {ss::bsdf::ModelKind::ghs};
    const auto fit = ss::inverse::fit_brdf(data, options).fits[0];
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
