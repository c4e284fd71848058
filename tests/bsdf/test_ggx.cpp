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

// ---------------------------------------------------------------------------------------------------------------
// Anisotropic distributions and the anisotropic GgxBsdf.

namespace {

// int f(h) dw over the hemisphere, midpoint rule in (cos theta, phi).
template <class F>
double hemisphere_midpoint(F f, int nt = 4000, int np = 256) {
    double sum = 0;
    for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
            const double c = (i + 0.5) / nt, phi = kTwoPi * (j + 0.5) / np, s = std::sqrt(1 - c * c);
            sum += f(Vec3(s * std::cos(phi), s * std::sin(phi), c));
        }
    return sum * (1.0 / nt) * (kTwoPi / np);
}

// pbrt-v4's anisotropic Trowbridge-Reitz and Beckmann D in tan / azimuth form, written here.
double pbrt_ggx_d(const Vec3& h, double ax, double ay) {
    const double c2 = h.z * h.z, t2 = (1 - c2) / c2, phi = std::atan2(h.y, h.x);
    const double e = t2 * (std::pow(std::cos(phi) / ax, 2) + std::pow(std::sin(phi) / ay, 2));
    return 1.0 / (kPi * ax * ay * c2 * c2 * (1 + e) * (1 + e));
}
double pbrt_beckmann_d(const Vec3& h, double ax, double ay) {
    const double c2 = h.z * h.z, t2 = (1 - c2) / c2, phi = std::atan2(h.y, h.x);
    const double e = t2 * (std::pow(std::cos(phi) / ax, 2) + std::pow(std::sin(phi) / ay, 2));
    return std::exp(-e) / (kPi * ax * ay * c2 * c2);
}

test::Chi2Subject normal_subject(std::function<Vec3(Vec2)> sample, std::function<double(const Vec3&)> density) {
    test::Chi2Subject subject;
    subject.sample = [sample, density](double, Vec2 u) -> std::optional<test::DirectionSample> {
        const Vec3 h = sample(u);
        return test::DirectionSample{h, density(h), 0, false};
    };
    subject.pdf = density;
    return subject;
}

constexpr std::pair<double, double> kAnisotropicAlphas[] = {{0.1, 0.4}, {0.6, 0.15}, {0.3, 1.2}};

}  // namespace

TEST(AnisotropicMicrofacet, DMatchesPbrtAndIsNormalised) {
    for (auto [ax, ay] : kAnisotropicAlphas) {
        const GgxDistribution ggx(ax, ay);
        const BeckmannDistribution beckmann(ax, ay);
        for (double t : {0.0, 20.0, 50.0, 80.0})
            for (double p : {0.0, 0.7, 2.0, 4.1}) {
                const Vec3 h = spherical_direction(t * kDegree, p);
                const double g = pbrt_ggx_d(h, ax, ay), b = pbrt_beckmann_d(h, ax, ay);
                EXPECT_NEAR(ggx.D(h), g, 1e-12 * g) << ax << " " << ay;
                EXPECT_NEAR(beckmann.D(h), b, 1e-12 * b) << ax << " " << ay;  // 0 where it underflows
            }
        const Vec3 wi = spherical_direction(60 * kDegree, 0.9);
        EXPECT_NEAR(hemisphere_midpoint([&](const Vec3& h) { return ggx.D(h) * h.z; }), 1.0, 2e-3) << ax << " " << ay;
        EXPECT_NEAR(hemisphere_midpoint([&](const Vec3& h) { return ggx.visible_density(wi, h); }), 1.0, 2e-3);
        EXPECT_NEAR(hemisphere_midpoint([&](const Vec3& h) { return beckmann.projected_density(h); }), 1.0, 2e-3);
    }
}

TEST(AnisotropicMicrofacet, EqualAlphasAgreeWithTheIsotropicForm) {
    // The anisotropic branch at alpha_x = alpha_y (1 ulp apart, so that it is taken) against the isotropic code.
    for (double a : {0.05, 0.3, 1.5}) {
        const double b = std::nextafter(a, 1.0);
        const GgxDistribution iso(a), aniso(a, b);
        const BeckmannDistribution biso(a), baniso(a, b);
        for (double t : {0.0, 30.0, 70.0, 89.0}) {
            const Vec3 w = spherical_direction(t * kDegree, 1.1);
            EXPECT_NEAR(aniso.D(w), iso.D(w), 1e-12 * iso.D(w));
            EXPECT_NEAR(aniso.lambda(w), iso.lambda(w), 1e-12 * (1 + iso.lambda(w)));
            EXPECT_NEAR(baniso.D(w), biso.D(w), 1e-12 * biso.D(w));
            EXPECT_NEAR(baniso.lambda(w), biso.lambda(w), 1e-12 * (1 + biso.lambda(w)));
        }
    }
}

TEST(AnisotropicMicrofacet, SamplersChiSquare) {
    const double level = test::sidak(0.01, 3 * 4 + 3);
    for (auto [ax, ay] : kAnisotropicAlphas) {
        const GgxDistribution ggx(ax, ay);
        for (double t : {0.0, 40.0, 75.0, 88.0}) {
            const Vec3 wi = spherical_direction(t * kDegree, 0.6);
            const auto r = test::chi2_test(normal_subject([&](Vec2 u) { return ggx.sample_visible(wi, u); },
                                                          [&](const Vec3& h) { return ggx.visible_density(wi, h); }),
                                           300000);
            EXPECT_GT(r.p_value, level) << "ggx " << ax << " " << ay << " theta " << t << ": " << r.summary();
            EXPECT_LT(r.pdf_mismatch, 1e-12) << r.summary();
        }
        const BeckmannDistribution beckmann(ax, ay);
        const auto r = test::chi2_test(normal_subject([&](Vec2 u) { return beckmann.sample_projected(u); },
                                                      [&](const Vec3& h) { return beckmann.projected_density(h); }),
                                       300000);
        EXPECT_GT(r.p_value, level) << "beckmann " << ax << " " << ay << ": " << r.summary();
    }
}

namespace {

// Directional albedo of the anisotropic GGX perfect conductor over the microfacet slopes (no BRDF evaluation): the
// slopes p = (ax r cos phi, ay r sin phi) of density P22 r dr dphi (r = tan beta gives sin beta cos beta / pi), the
// visible fraction (i.m) / (m_z cos i), and height-correlated G2 with the anisotropic Lambda written here.
double anisotropic_slope_albedo(double ax, double ay, const Vec3& wi) {
    const auto smith = [&](const Vec3& w) {
        return 0.5 * (std::sqrt(w.z * w.z + ax * ax * w.x * w.x + ay * ay * w.y * w.y) / w.z - 1.0);
    };
    const double lambda_i = smith(wi);
    const int nb = 1500, np = 720;
    double sum = 0;
    for (int i = 0; i < nb; ++i) {
        const double beta = 0.5 * kPi * (i + 0.5) / nb, r = std::tan(beta);
        for (int j = 0; j < np; ++j) {
            const double phi = kTwoPi * (j + 0.5) / np;
            const Vec3 m = normalize(Vec3(-ax * r * std::cos(phi), -ay * r * std::sin(phi), 1.0));
            const double im = dot(wi, m);
            if (im <= 0) continue;
            const Vec3 o = 2 * im * m - wi;
            if (o.z <= 0) continue;
            sum += std::sin(beta) * std::cos(beta) / kPi * im / (m.z * wi.z) / (1 + lambda_i + smith(o));
        }
    }
    return sum * (0.5 * kPi / nb) * (kTwoPi / np);
}

}  // namespace

TEST(AnisotropicGgx, AlbedoMatchesTheSlopeIntegralAndSamplingChiSquare) {
    const auto perfect = material::Conductor::perfect();
    const double level = test::sidak(0.01, 8);
    for (auto [au, av] : {std::pair{0.15, 0.5}, std::pair{0.6, 0.2}}) {
        for (double lay : {0.0, 35.0}) {
            const GgxBsdf bsdf(perfect, Vec2(au, av), lay * kDegree);
            for (double t : {20.0, 70.0}) {
                const Vec3 wi = spherical_direction(t * kDegree, 0.4);
                const auto r = test::chi2_test(bsdf, wi, 550.0, 300000);
                EXPECT_GT(r.p_value, level) << au << " " << av << " lay " << lay << " theta " << t << ": " << r.summary();
                EXPECT_LT(r.pdf_mismatch, 1e-9) << r.summary();
                EXPECT_LT(r.weight_mismatch, 1e-9) << r.summary();
                // The albedo over the hemisphere against the slope-space integral in the lay frame.
                const Vec3 wi_lay(std::cos(lay * kDegree) * wi.x + std::sin(lay * kDegree) * wi.y,
                                  -std::sin(lay * kDegree) * wi.x + std::cos(lay * kDegree) * wi.y, wi.z);
                const double albedo =
                    hemisphere_midpoint([&](const Vec3& wo) { return bsdf.eval(wi, wo, 550.0) * wo.z; }, 3000, 720);
                const double reference = anisotropic_slope_albedo(au, av, wi_lay);
                EXPECT_NEAR(albedo, reference, 2e-3) << au << " " << av << " lay " << lay << " theta " << t;
                EXPECT_LE(reference, 1.0);
            }
        }
    }
}

TEST(AnisotropicGgx, LayAngleRotatesTheLobe) {
    // A + 90 deg with alpha_u and alpha_v swapped is the same surface; and the lobe at lay A is the lay-0 lobe of the
    // directions rotated by -A.
    const auto al = material::Conductor::from_name("Al");
    const double a = 0.4;
    const GgxBsdf base(al, Vec2(0.1, 0.35), a), swapped(al, Vec2(0.35, 0.1), a + 0.5 * kPi), aligned(al, Vec2(0.1, 0.35), 0);
    const auto rotate = [](const Vec3& w, double angle) {
        return Vec3(std::cos(angle) * w.x - std::sin(angle) * w.y, std::sin(angle) * w.x + std::cos(angle) * w.y, w.z);
    };
    for (double ti : {0.0, 30.0, 65.0})
        for (double to : {10.0, 45.0, 80.0})
            for (double po : {0.0, 1.0, 2.5, 4.0}) {
                const Vec3 wi = spherical_direction(ti * kDegree, 0.2), wo = spherical_direction(to * kDegree, po);
                const double f = base.eval(wi, wo, 600.0);
                EXPECT_NEAR(swapped.eval(wi, wo, 600.0), f, 1e-12 * (1 + f));
                EXPECT_NEAR(aligned.eval(rotate(wi, -a), rotate(wo, -a), 600.0), f, 1e-12 * (1 + f));
                EXPECT_NEAR(swapped.pdf(wi, wo, 600.0), base.pdf(wi, wo, 600.0), 1e-12 * (1 + base.pdf(wi, wo, 600.0)));
                // The packet (four wavelengths, reverse pdf) equals eval and pdf one at a time.
                WavelengthValues pdf{};
                const WavelengthValues lambdas{450.0, 520.0, 600.0, 700.0};
                const WavelengthValues packet = base.eval_packet(wi, wo, lambdas, &pdf);
                for (std::size_t k = 0; k < lambdas.size(); ++k) {
                    const double fk = base.eval(wi, wo, lambdas[k]), pk = base.pdf(wo, wi, lambdas[k]);
                    EXPECT_NEAR(packet[k], fk, 1e-12 * (1 + fk));
                    EXPECT_NEAR(pdf[k], pk, 1e-12 * (1 + pk));
                }
            }
}
