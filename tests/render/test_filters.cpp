// The reconstruction filters (filters/*.cpp): Mitsuba's footprints and profiles, integral 1, the sampler's
// distribution (chi-square) and weights (expectation 1, also inside a crop window), and an edge rendered through
// each filter, whose pixels must follow the filter's cumulative integral.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include <fmt/format.h>

#include "bsdf/chi2_harness.hpp"
#include "render_test_util.hpp"
#include "surfscatter/math/quadrature.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;

namespace {

struct FilterCase {
    std::string xml;     // the <rfilter> element
    double radius;       // Mitsuba's footprint
};

const std::vector<FilterCase>& filter_cases() {
    static const std::vector<FilterCase> cases = {
        {R"(<rfilter type="box"/>)", 0.5},
        {R"(<rfilter type="tent"/>)", 1.0},
        {R"(<rfilter type="tent"><float name="radius" value="1.5"/></rfilter>)", 1.5},
        {R"(<rfilter type="gaussian"/>)", 2.0},
        {R"(<rfilter type="gaussian"><float name="stddev" value="0.3"/></rfilter>)", 1.2},
        {R"(<rfilter type="mitchell"/>)", 2.0},
        {R"(<rfilter type="mitchell"><float name="B" value="0.5"/><float name="C" value="0.25"/></rfilter>)", 2.0},
        {R"(<rfilter type="catmullrom"/>)", 2.0},
        {R"(<rfilter type="lanczos"/>)", 3.0},
        {R"(<rfilter type="lanczos"><integer name="lobes" value="2"/></rfilter>)", 2.0},
    };
    return cases;
}

FilterPtr load_filter(const std::string& rfilter) {
    const std::string xml = "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">" + rfilter +
                            "</film></sensor></scene>";
    return load_scene_from_string(xml, "filter.xml")->film.filter;
}

// Integral of the normalised profile over [a, b], by adaptive Gauss-Kronrod split at the integers (where the
// piecewise filters have their kinks) and at the box's edges.
double integral(const ReconstructionFilter& f, double a, double b) {
    std::vector<double> cuts = {a};
    for (double x = std::ceil(a * 2) / 2; x < b; x += 0.5)
        if (x > a) cuts.push_back(x);
    cuts.push_back(b);
    double sum = 0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i)
        sum += math::integrate_adaptive([&](double x) { return f.eval(x); }, cuts[i], cuts[i + 1], 1e-12, 1e-14);
    return sum;
}

}  // namespace

TEST(Filters, FootprintProfileAndUnitIntegral) {
    for (const FilterCase& c : filter_cases()) {
        const FilterPtr f = load_filter(c.xml);
        EXPECT_DOUBLE_EQ(f->radius(), c.radius) << c.xml;
        EXPECT_NEAR(integral(*f, -c.radius, c.radius), 1.0, 1e-9) << c.xml;
        EXPECT_EQ(f->eval(c.radius + 1e-9), 0.0) << c.xml;
        EXPECT_EQ(f->eval(-c.radius - 0.01), 0.0) << c.xml;
        std::printf("[filter] %-80s radius %.2f, integral %.12f, integral |f| %.4f\n", c.xml.c_str(), f->radius(),
                    integral(*f, -c.radius, c.radius), f->absolute_integral());
    }
    // Closed-form profiles (normalised): tent 1/r at 0; Mitchell-Netravali integrates to 1 for every B, C, so its
    // value at 0 is (6 - 2B) / 6; Catmull-Rom interpolates (1 at 0, 0 at 1); the Gaussian minus its value at 4
    // sigma, normalised with erf.
    EXPECT_NEAR(load_filter(filter_cases()[2].xml)->eval(0), 1 / 1.5, 1e-12);
    EXPECT_NEAR(load_filter(filter_cases()[5].xml)->eval(0), (6 - 2.0 / 3) / 6, 1e-9);
    EXPECT_NEAR(load_filter(filter_cases()[6].xml)->eval(0), (6 - 2 * 0.5) / 6, 1e-9);
    EXPECT_NEAR(load_filter(filter_cases()[7].xml)->eval(0), 1.0, 1e-9);
    EXPECT_NEAR(load_filter(filter_cases()[7].xml)->eval(1.0), 0.0, 1e-9);
    const double sigma = 0.5, bias = std::exp(-8.0);
    const double gaussian_integral = sigma * std::sqrt(2 * kPi) * std::erf(4 / std::sqrt(2.0)) - bias * 8 * sigma;
    EXPECT_NEAR(load_filter(filter_cases()[3].xml)->eval(0), (1 - bias) / gaussian_integral, 1e-9);
    EXPECT_NEAR(load_filter(filter_cases()[3].xml)->eval(0.7),
                (std::exp(-0.49 / (2 * sigma * sigma)) - bias) / gaussian_integral, 1e-9);
}

TEST(Filters, SamplerMatchesItsDensityAndWeightsAverageToOne) {
    using surfscatter::bsdf::test::gamma_q;
    const double alpha = surfscatter::bsdf::test::sidak(0.01, static_cast<int>(filter_cases().size()));
    for (const FilterCase& c : filter_cases()) {
        const FilterPtr f = load_filter(c.xml);
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> uniform(0.0, 1.0);
        const int bins = 64;
        const long n = 200000;
        std::vector<double> observed(bins, 0.0);
        double sum_w = 0, sum_w2 = 0, sum_wx2 = 0;
        for (long i = 0; i < n; ++i) {
            const auto s = f->sample({uniform(rng), uniform(rng)});
            const int bin = std::clamp(static_cast<int>((s.offset.x + c.radius) / (2 * c.radius) * bins), 0, bins - 1);
            observed[static_cast<std::size_t>(bin)] += 1;
            sum_w += s.weight;
            sum_w2 += s.weight * s.weight;
            sum_wx2 += s.weight * s.offset.x * s.offset.x;
        }
        // Chi-square of the x offsets against the sampler's density, which is separable and symmetric:
        // p(x) = pdf(x, 0) / p(0) with p(0) = sqrt(pdf(0, 0)); each bin integrated by a 256-point midpoint rule.
        const double p0 = std::sqrt(f->pdf({0.0, 0.0}));
        double chi2 = 0;
        int dof = -1;
        for (int b = 0; b < bins; ++b) {
            const double width = 2 * c.radius / bins, a = -c.radius + width * b;
            double mass = 0;
            for (int k = 0; k < 256; ++k) mass += f->pdf({a + (k + 0.5) * width / 256, 0.0}) / p0 * width / 256;
            const double expected = mass * static_cast<double>(n);
            if (expected < 5) continue;
            const double o = observed[static_cast<std::size_t>(b)];
            chi2 += (o - expected) * (o - expected) / expected;
            ++dof;
        }
        const double p_value = gamma_q(0.5 * dof, 0.5 * chi2);
        const double count = static_cast<double>(n);
        const double mean_w = sum_w / count, error_w = std::sqrt(std::max(0.0, sum_w2 / count - mean_w * mean_w) / count);
        // E[w x^2] = int f(x) x^2 dx, the filter's second moment, computed by quadrature.
        const double moment = math::integrate_adaptive([&](double x) { return f->eval(x) * x * x; }, -c.radius, c.radius, 1e-12);
        std::printf("[filter sampler] %-80s chi2 %.1f dof %d p %.3g, E[w] = %.4f +- %.4f, E[w x^2] %.4f (exact %.4f)\n",
                    c.xml.c_str(), chi2, dof, p_value, mean_w, error_w, sum_wx2 / count, moment);
        EXPECT_GT(p_value, alpha) << c.xml;
        EXPECT_NEAR(mean_w, 1.0, 4 * error_w + 1e-12) << c.xml;
        EXPECT_NEAR(sum_wx2 / count, moment, 4 * std::sqrt(sum_w2 / count) * c.radius * c.radius / std::sqrt(count)) << c.xml;
        // Restricted to a window (a pixel at the film's edge): the weights still average to 1.
        double restricted = 0, restricted2 = 0;
        for (long i = 0; i < n; ++i) {
            const auto s = f->sample({uniform(rng), uniform(rng)}, {-0.3, -c.radius}, {c.radius, 0.6});
            EXPECT_TRUE(s.offset.x >= -0.3 && s.offset.y <= 0.6);
            restricted += s.weight;
            restricted2 += s.weight * s.weight;
        }
        const double mean_r = restricted / count;
        EXPECT_NEAR(mean_r, 1.0, 4 * std::sqrt(std::max(0.0, restricted2 / count - mean_r * mean_r) / count) + 1e-5) << c.xml;
    }
}

namespace {

// A camera 10 units above an emitting half-plane x > 0 (radiance 1 at every wavelength), 16 x 2 pixels of 0.1
// units: the edge falls on the boundary between columns 7 and 8 (world -x is the image's left, Mitsuba's camera).
std::string edge_scene(const std::string& rfilter, const std::string& film_extra, bool emitter_right) {
    return fmt::format(R"(<scene version="3.0.0">
        <integrator type="path"><integer name="max_depth" value="1"/></integrator>
        <sensor type="perspective"><float name="fov" value="{}"/>
            <transform name="to_world"><lookat origin="0, 0, 10" target="0, 0, 0" up="0, 1, 0"/></transform>
            <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="2"/>{}{}</film>
        </sensor>
        <shape type="rectangle"><transform name="to_world"><scale x="2.5" y="5" z="1"/><translate x="{}"/></transform>
            <emitter type="area"><spectrum name="radiance" value="360:1, 830:1"/></emitter></shape>
    </scene>)", 2 * std::atan(0.08) / kDegree, film_extra, rfilter, emitter_right ? 2.5 : -2.5);
}

}  // namespace

TEST(Filters, RenderedEdgeFollowsTheCumulativeIntegral) {
    for (const FilterCase& c : filter_cases()) {
        const FilterPtr f = load_filter(c.xml);
        const Film film = render_string(edge_scene(c.xml, "", true), 2048);
        for (int k = 0; k < 16; ++k) {
            // Pixel k sees the emitter where its sample offset exceeds 8 - (k + 0.5) pixels.
            const double threshold = 8 - (k + 0.5);
            const double expected = threshold >= c.radius ? 0.0 : threshold <= -c.radius ? 1.0 : integral(*f, threshold, c.radius);
            const double value = 0.5 * (film.xyz(k, 0).y + film.xyz(k, 1).y);
            EXPECT_NEAR(value, expected, 0.03 * f->absolute_integral() * f->absolute_integral()) << c.xml << " column " << k;
        }
    }
    // The crop window x >= 8 of a scene lit only at x < 8: without sample_border its pixels see nothing; with it,
    // the first column gathers the gaussian's tail from outside the window, int_{-2}^{-0.5} f.
    const std::string crop = R"(<integer name="crop_offset_x" value="8"/><integer name="crop_width" value="8"/>)";
    const Film closed = render_string(edge_scene(R"(<rfilter type="gaussian"/>)", crop, false), 512);
    const Film open = render_string(
        edge_scene(R"(<rfilter type="gaussian"/>)", crop + R"(<boolean name="sample_border" value="true"/>)", false), 2048);
    const FilterPtr gaussian = load_filter(R"(<rfilter type="gaussian"/>)");
    for (int y = 0; y < 2; ++y) EXPECT_EQ(closed.xyz(0, y).y, 0.0);
    EXPECT_NEAR(0.5 * (open.xyz(0, 0).y + open.xyz(0, 1).y), integral(*gaussian, -2, -0.5), 0.02);
}
