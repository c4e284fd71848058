// MapGhsBsdf (psd measured, measured_spectrum 2d): the GHS on a height map's 2-D periodogram. Samplers by chi-square,
// the directional albedo against R by a quadrature written for the tests (model_fixtures.hpp's midpoint rule over the
// hemisphere; disc_albedo.hpp's arc is for mirror-symmetric lobes), the 90 deg rotation of
// the map against the rotated BRDF, and the lobes against the ring route (isotropic map) and against the anisotropic
// GHS of the statistics an elliptical map was synthesised from (lobe_distance.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "chi2_harness.hpp"
#include "lobe_distance.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/bsdf/map_ghs.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

constexpr double kLambda = 550.0;

std::shared_ptr<const surface::MapStatistics> measured(const heightmap::HeightMap& map) {
    return std::make_shared<const surface::MapStatistics>(map, heightmap::Form::plane);
}

ModelOptions map_options(ModelKind model, std::shared_ptr<const surface::MapStatistics> stats,
                         MeasuredSpectrum spectrum = MeasuredSpectrum::two_d) {
    ModelOptions o;
    o.model = model;
    o.surface.psd = PsdKind::measured;
    o.surface.measured_psd = std::move(stats);
    o.surface.measured_spectrum = spectrum;
    return o;
}

// Midpoint sum of f(zeta) h^2 over the nodes of the lattice of spacing h through 0 within `radius` of `centre`, a node
// near the rim weighted by the share of its cell inside the disc (a linear ramp over one cell).
template <class F>
double disc_sum(Vec2 centre, double radius, double h, F&& f) {
    double sum = 0;
    const double outer = radius + 0.5 * h;
    for (long j = long(std::ceil((centre.y - outer) / h)); j <= long(std::floor((centre.y + outer) / h)); ++j)
        for (long i = long(std::ceil((centre.x - outer) / h)); i <= long(std::floor((centre.x + outer) / h)); ++i) {
            const Vec2 z(double(i) * h, double(j) * h);
            const double w = std::clamp(0.5 + (radius - std::hypot(z.x - centre.x, z.y - centre.y)) / h, 0.0, 1.0);
            if (w > 0) sum += w * f(z);
        }
    return sum * h * h;
}

// A periodic 256^2 map at 0.05 um (12.8 um) of a Gaussian ACV with l = 0.5 um.
heightmap::HeightMap gaussian_map(double sigma, std::uint64_t seed = 3) {
    return surface::synthesize_surface(surface::GaussianAcv(sigma, 0.5), {256, 256, 0.05}, seed);
}

// A periodic 256^2 map at 0.05 um of an elliptical KC surface (L_u 0.8 um, L_v 0.24 um, lay 25 deg).
heightmap::HeightMap elliptical_map() {
    return surface::synthesize_surface(
        surface::EllipticalStatistics(std::make_shared<surface::KCorrelation>(0.06, 0.8, 3.0), 0.3, 25 * kDegree),
        {256, 256, 0.05}, 12);
}

Vec3 direction_deg(double theta, double phi) {
    return spherical_direction(theta * kDegree, phi * kDegree);
}

// The map turned by +90 deg about its centre: h'(i, j) = h(j, n - 1 - i), so that h'(R r) = h(r), R: (x, y) -> (-y, x).
heightmap::HeightMap rotated(const heightmap::HeightMap& map) {
    const std::size_t n = map.nx();
    std::vector<double> h(n * n);
    for (std::size_t j = 0; j < n; ++j)
        for (std::size_t i = 0; i < n; ++i) h[j * n + i] = map(j, n - 1 - i);
    return heightmap::HeightMap(n, n, map.spacing_x(), map.spacing_y(), std::move(h), "rotated");
}

Vec3 turn(const Vec3& w) { return {-w.y, w.x, w.z}; }

}  // namespace

TEST(MapGhs, FactoryMakesItForGhsAndSsaAndSaysSo) {
    const auto stats = measured(gaussian_map(0.05));
    std::vector<std::string> notes;
    const auto ghs = make_bsdf(map_options(ModelKind::ghs, stats), &notes);
    EXPECT_NE(dynamic_cast<const MapGhsBsdf*>(ghs.get()), nullptr);
    EXPECT_FALSE(ghs->isotropic());
    ASSERT_EQ(notes.size(), 2u);
    EXPECT_NE(notes[0].find("band zeta"), std::string::npos) << notes[0];  // the measured-route notes stay
    EXPECT_NE(notes[1].find("measured 2-D spectrum"), std::string::npos) << notes[1];
    const auto ssa = make_bsdf(map_options(ModelKind::ghs_ssa, stats));
    EXPECT_NE(dynamic_cast<const MapGhsBsdf*>(ssa.get()), nullptr);
    const auto ring = make_bsdf(map_options(ModelKind::ghs, stats, MeasuredSpectrum::ring));
    EXPECT_EQ(dynamic_cast<const MapGhsBsdf*>(ring.get()), nullptr);
    notes.clear();
    make_bsdf(map_options(ModelKind::two_scale, stats), &notes);
    ASSERT_FALSE(notes.empty());
    EXPECT_NE(notes.front().find("ring average"), std::string::npos) << notes.front();
    EXPECT_THROW(ghs->eval(direction_deg(30, 0), direction_deg(30, 180), 300.0), Error);  // below 360 nm
    const Vec3 nan_incidence(std::nan(""), 0.1, 0.9);  // no NaN leaves the public functions
    EXPECT_EQ(ghs->eval(nan_incidence, direction_deg(30, 180), kLambda), 0.0);
    EXPECT_EQ(ghs->pdf(nan_incidence, direction_deg(30, 180), kLambda), 0.0);
}

TEST(MapGhs, SamplersPassChiSquare) {
    struct Case { ModelKind model; double sigma, theta_i, phi_i; };
    const std::vector<Case> cases = {
        {ModelKind::ghs, 0.02, 30.0, 0.0},     // g0 ~ 0.15
        {ModelKind::ghs, 0.08, 50.0, 70.0},    // ~ 1.1
        {ModelKind::ghs, 0.2, 20.0, 200.0},    // ~ 15
        {ModelKind::ghs_ssa, 0.05, 60.0, 35.0},
    };
    const double alpha = test::sidak(0.01, int(cases.size()));
    for (const Case& c : cases) {
        const auto bsdf = make_bsdf(map_options(c.model, measured(gaussian_map(c.sigma))));
        const auto r = test::chi2_test_wedge(*bsdf, direction_deg(c.theta_i, c.phi_i), kLambda, 200000);
        EXPECT_GT(r.p_value, alpha) << r.summary();
        EXPECT_LT(r.pdf_mismatch, 1e-9) << r.summary();
        EXPECT_LT(r.weight_mismatch, 1e-9) << r.summary();
        EXPECT_LE(r.expected_total, 1.0 + 1e-3) << r.summary();
    }
}

// Full GHS with renormalisation: albedo = R (1 for the perfect conductor) at every incidence azimuth.
TEST(MapGhs, AlbedoIsROverEveryIncidenceAzimuth) {
    double worst = 0;
    for (double sigma : {0.03, 0.12}) {
        const auto bsdf = make_bsdf(map_options(ModelKind::ghs, measured(gaussian_map(sigma, 8))));
        for (double theta_i : {0.0, 40.0, 75.0})
            for (double phi_i : {0.0, 25.0, 60.0, 90.0, 135.0}) {
                const double albedo = test::directional_albedo(*bsdf, direction_deg(theta_i, phi_i), kLambda);
                worst = std::max(worst, std::abs(albedo - 1.0));
                EXPECT_NEAR(albedo, 1.0, 5e-3) << sigma << " " << theta_i << " " << phi_i;
            }
    }
    std::printf("largest |albedo - R|: %.3g\n", worst);
}

// direct()'s visible-disc integrals (the product rule on cells of k / 64: MapGhsBsdf::kDiscCells) against the midpoint
// sum written here on the map's own lattice spacing (the finest any row has), of sigma_rel^2 / sigma_h^2 (P-hat over the
// disc) and of the albedo normalisation's lobe integral, on a 512^2 map at 0.2 um (cells 3x coarser than the
// lattice): within 5e-3, the size of the tables' own interpolation error (measured 2.5e-3 and 4.5e-3; the albedo
// test above, against an independent quadrature of the eval, stays at 1.2e-3).
TEST(MapGhs, DiscIntegralsOnCellsMatchTheLatticeSum) {
    const auto stats = std::make_shared<const surface::MapStatistics>(
        surface::synthesize_surface(surface::KCorrelation(0.04, 2.0, 3.0), {512, 512, 0.2}, 4), heightmap::Form::plane);
    const auto bsdf = make_bsdf(map_options(ModelKind::ghs, stats));
    const auto& map_ghs = dynamic_cast<const MapGhsBsdf&>(*bsdf);
    const surface::SpectrumLobes2d& lobes = map_ghs.lobes();
    const double k = kTwoPi / (kLambda * 1e-3), h = kTwoPi / (512 * 0.2);
    double worst_sigma = 0, worst_norm = 0;
    for (double theta_i : {0.0, 25.0, 50.0, 75.0})
        for (double phi_i : {0.0, 70.0}) {
            const Vec3 wi = direction_deg(theta_i, phi_i);
            const Vec2 centre(k * wi.x, k * wi.y);
            const GhsBsdf::Direct d = map_ghs.direct(wi, kLambda);
            // Midpoint sums over the lattice nodes in the disc, a node on the rim weighted by its share (linear ramp).
            double mass = 0, lobe = 0;
            const double ci = wi.z;
            const double sigma = lobes.sigma_h() * std::sqrt(std::clamp(
                                     disc_sum(centre, k, h, [&](Vec2 z) { return lobes.first_order(z); }), 0.0, 1.0));
            mass = sigma / lobes.sigma_h();
            lobe = disc_sum(centre, k, h, [&](Vec2 z) {
                const double ox = z.x / k - wi.x, oy = z.y / k - wi.y;
                const double co = std::sqrt(std::max(0.0, 1.0 - ox * ox - oy * oy)), c = k * sigma * (ci + co);
                return lobes.eval(c * c, z);
            });
            const double a = 2 * k * sigma * ci, norm = -std::expm1(-a * a) / lobe;
            worst_sigma = std::max(worst_sigma, std::abs(d.sigma / sigma - 1));
            worst_norm = std::max(worst_norm, std::abs(d.norm / norm - 1));
            EXPECT_GT(mass, 0.5);
        }
    std::printf("disc integrals on cells against the lattice sum: sigma %.3g, N %.3g\n", worst_sigma, worst_norm);
    EXPECT_LT(worst_sigma, 5e-3);
    EXPECT_LT(worst_norm, 5e-3);
}

// The tables against direct() between their nodes, every 3.1 deg of phi_i: sigma within 2.7e-3 and N within 3.2e-3 on
// the Gaussian map, 7.4e-3 and 5.3e-3 on the elliptical one (sigma_rel is a lattice sum, stepped where lattice points
// cross the visible disc's rim; twice the azimuth nodes only halve it).
TEST(MapGhs, TablesMatchDirectValues) {
    for (const heightmap::HeightMap& map : {gaussian_map(0.08, 4), elliptical_map()}) {
        const auto bsdf = make_bsdf(map_options(ModelKind::ghs, measured(map)));
        const auto& map_ghs = dynamic_cast<const MapGhsBsdf&>(*bsdf);
        double sigma_error = 0, norm_error = 0;
        for (double theta_i : {7.3, 33.1, 61.7, 80.2})
            for (double phi_i = 1.3; phi_i < 360; phi_i += 3.1) {
                const Vec3 wi = direction_deg(theta_i, phi_i);
                const GhsBsdf::Direct d = map_ghs.direct(wi, kLambda);
                sigma_error = std::max(sigma_error, std::abs(map_ghs.sigma(wi, kLambda) / d.sigma - 1));
                norm_error = std::max(norm_error, std::abs(map_ghs.normalization(wi, kLambda) / d.norm - 1));
            }
        std::printf("%s: tables against direct: sigma %.3g, N %.3g\n", map.origin().c_str(), sigma_error, norm_error);
        EXPECT_LT(sigma_error, 1e-2);
        EXPECT_LT(norm_error, 8e-3);
    }
}

// tabulate() (what a render calls first): every wavelength node of the range built over two threads, each with its
// own disc bins (they once shared one set, rebuilt by every integral when two threads built different nodes), and the
// tables then read match direct() as in TablesMatchDirectValues, between the nodes too; a range below 360 nm is an
// Error naming it.
TEST(MapGhs, TabulateBuildsEveryNodeOfTheRangeOverThreads) {
    const auto bsdf = make_bsdf(map_options(ModelKind::ghs, measured(gaussian_map(0.08, 5))));
    const auto& map_ghs = dynamic_cast<const MapGhsBsdf&>(*bsdf);
    map_ghs.tabulate(530, 565, 2);
    double sigma_error = 0, norm_error = 0;
    for (double lambda : {530.0, 541.3, 552.9, 565.0})
        for (double theta_i : {12.1, 47.7})
            for (double phi_i = 2.1; phi_i < 360; phi_i += 29.3) {
                const Vec3 wi = direction_deg(theta_i, phi_i);
                const GhsBsdf::Direct d = map_ghs.direct(wi, lambda);
                sigma_error = std::max(sigma_error, std::abs(map_ghs.sigma(wi, lambda) / d.sigma - 1));
                norm_error = std::max(norm_error, std::abs(map_ghs.normalization(wi, lambda) / d.norm - 1));
            }
    EXPECT_LT(sigma_error, 1e-2);
    EXPECT_LT(norm_error, 8e-3);
    std::string message;
    try {
        map_ghs.tabulate(300, 565, 1);
    } catch (const Error& e) {
        message = e.what();
    }
    EXPECT_NE(message.find("wavelengths 300 .. 565 nm outside"), std::string::npos) << message;
}

// The eval reads the azimuth linearly between kRefinement points per tabulated interval, on the periodic cubic
// through the tabulated nodes: against that cubic written here, through direct() at the nodes (at an incidence node,
// where the cubic in cos theta_i is exact, and a wavelength node), on an elliptical map whose sigma_rel and N vary
// strongly with the azimuth. Linear over 96 azimuths it adds 3.5e-4 to ln sigma and 7.2e-4 to ln N (192: 8e-5 and
// 1.7e-4, the h^2 of linear interpolation), where the cubic is 5.3e-3 and 3.8e-3 from direct() (sigma_rel's lattice
// steps).
TEST(MapGhs, RefinedAzimuthsFollowTheCubicThroughTheNodes) {
    const heightmap::HeightMap map = elliptical_map();
    const auto bsdf = make_bsdf(map_options(ModelKind::ghs, measured(map)));
    const auto& map_ghs = dynamic_cast<const MapGhsBsdf&>(*bsdf);
    const NodeAxis axis = ghs_incidence_axis();
    const double lambda = ghs_wavelength_axis().node(ghs_wavelength_axis().position(kLambda).interval);
    constexpr int n = MapGhsBsdf::kAzimuthNodes;
    double sigma_error = 0, norm_error = 0, sigma_range = 0, cubic_sigma_error = 0, cubic_norm_error = 0;
    for (int j : {20, 45}) {  // theta_i about 18 and 52 deg
        const double c = axis.node(j), s = std::sqrt(1 - c * c);
        auto incidence = [&](double phi) { return Vec3(s * std::cos(phi), s * std::sin(phi), c); };
        std::vector<double> log_sigma(n), log_norm(n);
        for (int a = 0; a < n; ++a) {
            const GhsBsdf::Direct d = map_ghs.direct(incidence(a * kPi / n), lambda);
            log_sigma[std::size_t(a)] = std::log(d.sigma);
            log_norm[std::size_t(a)] = std::log(d.norm);
        }
        sigma_range = std::max(sigma_range, *std::max_element(log_sigma.begin(), log_sigma.end()) -
                                                *std::min_element(log_sigma.begin(), log_sigma.end()));
        for (double phi_deg = 0.3; phi_deg < 360; phi_deg += 1.7) {
            const double x = std::fmod(phi_deg * kDegree, kPi) / (kPi / n);
            const int base = int(x);
            const double t = x - base + 1.0;  // among the nodes base - 1 .. base + 2
            double cubic_sigma = 0, cubic_norm = 0;
            for (int m = 0; m < 4; ++m) {
                double w = 1;  // Lagrange weight of node m at t
                for (int q = 0; q < 4; ++q)
                    if (q != m) w *= (t - q) / double(m - q);
                const std::size_t node = std::size_t((base - 1 + m + n) % n);
                cubic_sigma += w * log_sigma[node];
                cubic_norm += w * log_norm[node];
            }
            const Vec3 wi = incidence(phi_deg * kDegree);
            sigma_error = std::max(sigma_error, std::abs(std::log(map_ghs.sigma(wi, lambda)) - cubic_sigma));
            const GhsBsdf::Direct d = map_ghs.direct(wi, lambda);
            cubic_sigma_error = std::max(cubic_sigma_error, std::abs(std::log(d.sigma) - cubic_sigma));
            cubic_norm_error = std::max(cubic_norm_error, std::abs(std::log(d.norm) - cubic_norm));
            norm_error = std::max(norm_error, std::abs(std::log(map_ghs.normalization(wi, lambda)) - cubic_norm));
        }
    }
    std::printf("refined azimuths against the cubic: ln sigma %.3g, ln N %.3g (ln sigma spans %.3g over phi_i); the "
                "cubic against direct(): %.3g, %.3g\n",
                sigma_error, norm_error, sigma_range, cubic_sigma_error, cubic_norm_error);
    EXPECT_GT(sigma_range, 0.05);  // the case does test the azimuth
    EXPECT_LT(sigma_error, 5e-4);
    EXPECT_LT(norm_error, 1e-3);
    // What the refinement adds is small beside the cubic's own error between the nodes.
    EXPECT_LT(sigma_error, 0.2 * cubic_sigma_error);
    EXPECT_LT(norm_error, 0.3 * cubic_norm_error);
}

TEST(MapGhs, MapRotatedBy90DegreesGivesTheRotatedBrdf) {
    const heightmap::HeightMap map = elliptical_map();
    const auto a = make_bsdf(map_options(ModelKind::ghs, measured(map)));
    const auto b = make_bsdf(map_options(ModelKind::ghs, measured(rotated(map))));
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0;
    for (int n = 0; n < 400; ++n) {
        const Vec3 wi = direction_deg(80 * u(rng), 360 * u(rng));
        const Vec3 wo = direction_deg(85 * u(rng), 360 * u(rng));
        const double fa = a->eval(wi, wo, kLambda), fb = b->eval(turn(wi), turn(wo), kLambda);
        const double scale = std::max(fa, a->eval(wi, reflect_about_normal(wi), kLambda) * 1e-3);
        worst = std::max(worst, std::abs(fa - fb) / scale);
    }
    std::printf("rotated map: largest relative difference %.3g\n", worst);
    EXPECT_LT(worst, 1e-6);
}

// Isotropic map: the 2-D lobe against the ring average's, a noise-limited comparison: the periodogram's bins scatter
// by 100 % about their ring's mean, which the first order shows bin by bin (lobe distance 0.29 measured at g0 = 1.9)
// and the higher orders, convolutions over many bins, average out: at g0 ~ 20 (sigma 0.2 um) the lobes agree closely.
TEST(MapGhs, IsotropicMapGivesTwoDCloseToRing) {
    for (const auto& [sigma, tolerance] : {std::pair{0.06, 0.4}, std::pair{0.2, 0.05}}) {
        const auto stats = measured(gaussian_map(sigma, 21));
        const auto two_d = make_bsdf(map_options(ModelKind::ghs, stats));
        const auto ring = make_bsdf(map_options(ModelKind::ghs, stats, MeasuredSpectrum::ring));
        const double d = test::lobe_distance(*two_d, *ring, kLambda);
        std::printf("isotropic map, sigma %.2g um: lobe distance 2d against ring %.3g\n", sigma, d);
        EXPECT_LT(d, tolerance) << sigma;
    }
}

// Elliptical KC map: the 2-D lobe against AnisotropicGhsBsdf on the statistics the map was synthesised from
// (statistical: one 512^2 realisation, 25 LU wide, g0 ~ 1.9: the periodogram's bin scatter dominates, measured 0.13;
// the ring average, blind to the lay, is 0.66 away).
TEST(MapGhs, EllipticalMapFollowsTheAnisotropicGhs) {
    const double sigma = 0.06, lu = 1.0, lv = 0.35, lay = 30.0;
    const heightmap::HeightMap map = surface::synthesize_surface(
        surface::EllipticalStatistics(std::make_shared<surface::KCorrelation>(sigma, lu, 3.0), lv, lay * kDegree),
        {512, 512, 0.05}, 31);
    ModelOptions truth = test::kc_options(ModelKind::ghs, sigma, lu, 3.0);
    truth.surface.corr_length_v = lv;
    truth.surface.lay_angle = lay;
    const auto exact = make_bsdf(truth);
    const auto two_d = make_bsdf(map_options(ModelKind::ghs, measured(map)));
    const auto ring = make_bsdf(map_options(ModelKind::ghs, measured(map), MeasuredSpectrum::ring));
    const double d_two_d = test::lobe_distance(*two_d, *exact, kLambda), d_ring = test::lobe_distance(*ring, *exact, kLambda);
    std::printf("elliptical map: lobe distance to the anisotropic GHS, 2d %.3g, ring %.3g\n", d_two_d, d_ring);
    EXPECT_LT(d_two_d, 0.2);
    EXPECT_LT(d_two_d, 0.5 * d_ring);
}

// ggx_stats on an elliptical Gaussian-ACV map: alpha_u, alpha_v and the lay from the map's slope covariance against
// the elliptical GGX of the statistics it was synthesised from (sqrt(2 <h_axis^2>), factory.cpp), statistical (one
// 512^2 realisation 25 LU wide); the ring route keeps the isotropic rms slope.
TEST(MapGhs, GgxTakesTheSlopeCovariance) {
    const double sigma = 0.05, lu = 1.0, lv = 0.4, lay = 30.0;
    const heightmap::HeightMap map = surface::synthesize_surface(
        surface::EllipticalStatistics(std::make_shared<surface::GaussianAcv>(sigma, lu), lv, lay * kDegree),
        {512, 512, 0.05}, 17);
    ModelOptions truth;
    truth.model = ModelKind::ggx;
    truth.surface.psd = PsdKind::gaussian;
    truth.surface.sigma = sigma;
    truth.surface.corr_length = lu;
    truth.surface.corr_length_v = lv;
    truth.surface.lay_angle = lay;
    const auto expected = make_bsdf(truth);
    ModelOptions o = map_options(ModelKind::ggx, nullptr);
    o.surface.measured_psd = nullptr;
    o.surface.surface_file = "elliptical map";
    o.surface.height_map = std::make_shared<const heightmap::HeightMap>(map);
    std::vector<std::string> notes;
    const auto two_d = make_bsdf(o, &notes);
    const auto& g = dynamic_cast<const GgxBsdf&>(*two_d);
    const auto& e = dynamic_cast<const GgxBsdf&>(*expected);
    std::printf("slope covariance: alpha_u %.4g (truth %.4g), alpha_v %.4g (%.4g), lay %.3g deg\n", g.alpha_uv(kLambda).x,
                e.alpha_uv(kLambda).x, g.alpha_uv(kLambda).y, e.alpha_uv(kLambda).y, g.lay_angle() / kDegree);
    EXPECT_NEAR(g.alpha_uv(kLambda).x / e.alpha_uv(kLambda).x, 1.0, 0.05);
    EXPECT_NEAR(g.alpha_uv(kLambda).y / e.alpha_uv(kLambda).y, 1.0, 0.05);
    EXPECT_NEAR(std::remainder(g.lay_angle() / kDegree - lay, 180.0), 0.0, 3.0);
    EXPECT_NE(notes.back().find("slope covariance"), std::string::npos) << notes.back();
    o.surface.measured_spectrum = MeasuredSpectrum::ring;
    const auto ring = make_bsdf(o);
    EXPECT_TRUE(ring->isotropic());
}
