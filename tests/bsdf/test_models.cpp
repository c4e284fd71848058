// SSA against GHS, the gamma = 3 GGX identity, energy bounds of every model, factory validation, extreme inputs, the
// renderer's packet call against the one-wavelength interface.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "model_fixtures.hpp"
#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/core/error.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

TEST(Ssa, EqualsGhsAtSmallG) {
    // g0 = 1e-3 at theta_i = 30 deg; k L = 126 so the lobe is small compared with the visible disc.
    const double lambda = 500.0, length = 10.0, theta = 30.0;
    const double sigma = test::sigma_for_g(1e-3, lambda, theta);
    for (double gamma : {2.5, 3.0, 4.0}) {
        const auto ghs = make_bsdf(test::kc_options(ModelKind::ghs, sigma, length, gamma));
        auto energy_options = test::kc_options(ModelKind::ghs_ssa, sigma, length, gamma);
        const auto energy = make_bsdf(energy_options);
        energy_options.ssa_form = SsaForm::strict;
        const auto strict = make_bsdf(energy_options);
        const Vec3 wi = spherical_direction(theta * kDegree, 0.0);
        for (double d : {0.0, 0.2, 1.0, 3.0, 8.0})
            for (double phi : {kPi, kPi + 0.5}) {
                const Vec3 wo = spherical_direction((theta + d) * kDegree, phi);
                const double f = ghs->eval(wi, wo, lambda);
                EXPECT_NEAR(energy->eval(wi, wo, lambda), f, 0.01 * f) << gamma << " " << d;
                EXPECT_NEAR(strict->eval(wi, wo, lambda), f, 0.01 * f) << gamma << " " << d;
            }
        EXPECT_NEAR(energy->delta_reflectance(wi, lambda), ghs->delta_reflectance(wi, lambda), 1e-12);
    }
}

// THEORY 4.3: for gamma = 3, k^2 P-hat(zeta) = (1 - a^2) D_GGX(h; a) / (4 cos^2 theta_d),
// a^2 = 1 / (1 + 4 k^2 L^2 cos^2 theta_d). The strict SSA lobe is F k^2 g_h P-hat (F = 1 here).
TEST(Ssa, Gamma3FirstOrderLobeIsGgx) {
    const double lambda = 633.0, length = 2.0, sigma = 0.01;
    auto o = test::kc_options(ModelKind::ghs_ssa, sigma, length, 3.0);
    o.ssa_form = SsaForm::strict;
    const auto ssa = make_bsdf(o);
    const double k = 2 * kPi / (lambda * 1e-3);
    double worst = 0;
    for (double ti : {0.0, 20.0, 50.0, 75.0})
        for (double to : {0.0, 10.0, 35.0, 60.0, 85.0})
            for (double phi : {0.3, 2.0, kPi}) {
                const Vec3 wi = spherical_direction(ti * kDegree, 0.0), wo = spherical_direction(to * kDegree, phi);
                const double gh = std::pow(k * sigma * (wi.z + wo.z), 2);
                const double lobe = ssa->eval(wi, wo, lambda) / gh;
                const Vec3 h = normalize(wi + wo);
                const double cd = dot(wi, h);
                const double a2 = 1 / (1 + 4 * k * k * length * length * cd * cd);
                const double expected = (1 - a2) * GgxDistribution(std::sqrt(a2)).D(h) / (4 * cd * cd);
                worst = std::max(worst, std::abs(lobe / expected - 1));
            }
    EXPECT_LT(worst, 1e-9);
}

TEST(Models, NoModelExceedsOne) {
    const double lambda = 600.0;
    std::vector<ModelOptions> models;
    for (ModelKind m : {ModelKind::ghs, ModelKind::ghs_ssa, ModelKind::two_scale})
        for (double sigma : {0.02, 0.3})
            for (double gamma : {2.5, 4.0}) {
                auto o = test::kc_options(m, sigma, 1.5, gamma);
                o.cutoff_wavelengths = 5;
                models.push_back(o);
            }
    for (double alpha : {0.05, 0.5, 1.0}) {
        ModelOptions o;
        o.model = ModelKind::ggx;
        o.alpha_from = AlphaFrom::none;
        o.alpha = alpha;
        models.push_back(o);
    }
    for (const auto& o : models) {
        const auto bsdf = make_bsdf(o);
        for (double t : {0.0, 45.0, 75.0, 88.0}) {
            const Vec3 wi = spherical_direction(t * kDegree, 0.2);
            const double albedo = test::directional_albedo(*bsdf, wi, lambda, 240, 180);
            EXPECT_LE(albedo, 1.0 + 5e-3) << bsdf->name() << " sigma " << o.surface.sigma << " gamma "
                                          << o.surface.gamma << " alpha " << o.alpha << " theta_i " << t;
            // The GHS family carries exactly R (perfect conductor: 1); microfacet parts lose energy at grazing.
            if (o.model == ModelKind::ghs || o.model == ModelKind::ghs_ssa) { EXPECT_NEAR(albedo, 1.0, 5e-3) << bsdf->name(); }
        }
    }
}

TEST(Factory, RejectsBadOptionsNamingThem) {
    auto expect_error = [](const ModelOptions& o, const std::string& text) {
        try {
            make_bsdf(o);
            ADD_FAILURE() << "no error for " << text;
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
        }
    };
    expect_error(test::kc_options(ModelKind::ghs, 0.1, 1.0, 0.8), "gamma must be between 1.01 and 100 (KC), got 0.8");
    expect_error(test::kc_options(ModelKind::ghs, -1, 1.0, 3), "sigma must be between 1e-09 and 1e+09 um, got -1");
    expect_error(test::kc_options(ModelKind::ghs, 0.1, 0, 3), "corr_length must be between 1e-09 and 1e+09 um, got 0");
    ModelOptions ggx;
    ggx.model = ModelKind::ggx;
    ggx.alpha_from = AlphaFrom::none;
    expect_error(ggx, "alpha must be between 0.0001 and 100, got 0");
    ggx.alpha_from = AlphaFrom::measured;
    ggx.surface = test::kc_options(ModelKind::ggx, 0.1, 1.0, 2.5).surface;
    expect_error(ggx, "diverges");
    ModelOptions file;
    file.surface.psd = PsdKind::file;
    expect_error(file, "surface_file");
    EXPECT_THROW(parse_model("phong"), Error);
    EXPECT_EQ(parse_model("ghs-ssa"), ModelKind::ghs_ssa);
    EXPECT_EQ(parse_model("two_scale"), ModelKind::two_scale);
    EXPECT_EQ(parse_alpha_from("kc-link"), AlphaFrom::kc_link);
}

TEST(Ggx, AlphaFromSurfaceStatistics) {
    ModelOptions o = test::kc_options(ModelKind::ggx, 0.2, 1.0, 4.0);
    o.alpha_from = AlphaFrom::measured;  // <|grad h|^2> = 2 sigma^2 / ((gamma - 3) L^2) = 0.08
    EXPECT_NEAR(dynamic_cast<const GgxBsdf&>(*make_bsdf(o)).alpha(500), std::sqrt(0.08), 1e-7);
    o.surface.gamma = 3.0;
    o.surface.sigma = 1.0;
    o.alpha_from = AlphaFrom::smoothed;  // THEORY 4.1: gamma 3, L 1, sigma 1, s 0.3 -> 1.2884
    o.smoothing = 0.3;
    EXPECT_NEAR(dynamic_cast<const GgxBsdf&>(*make_bsdf(o)).alpha(500), std::sqrt(1.2884), 1e-4);
    o.alpha_from = AlphaFrom::kc_link;
    EXPECT_NEAR(dynamic_cast<const GgxBsdf&>(*make_bsdf(o)).alpha(200 * kPi), 1 / std::sqrt(401.0), 1e-12);
}

// ggx_stats on elliptical statistics: alpha_u, alpha_v = sqrt(2 <h_u^2>), sqrt(2 <h_v^2>) with <h_u^2> = sigma^2 /
// ((gamma - 3) LU^2) and <h_v^2> = sigma^2 / ((gamma - 3) LV^2) for KC (THEORY 4.1, 7.1), the lay angle passed on.
TEST(Ggx, EllipticalAlphaFromTheSlopeCovariance) {
    ModelOptions o = test::kc_options(ModelKind::ggx, 0.2, 2.0, 4.0);
    o.alpha_from = AlphaFrom::measured;
    o.surface.corr_length_v = 0.5;
    o.surface.lay_angle = 30;
    const auto& bsdf = dynamic_cast<const GgxBsdf&>(*make_bsdf(o));
    EXPECT_NEAR(bsdf.alpha_uv(500).x, std::sqrt(2 * 0.04 / 4.0), 1e-9);
    EXPECT_NEAR(bsdf.alpha_uv(500).y, std::sqrt(2 * 0.04 / 0.25), 1e-9);
    EXPECT_NEAR(bsdf.lay_angle(), 30 * kDegree, 1e-15);
    o.alpha_from = AlphaFrom::kc_link;
    const auto& linked = dynamic_cast<const GgxBsdf&>(*make_bsdf(o));
    EXPECT_EQ(linked.alpha_uv(600).x, kc_link_alpha(2.0, 600));
    EXPECT_EQ(linked.alpha_uv(600).y, kc_link_alpha(0.5, 600));
    // Divergent slopes are refused as for the isotropic surface; two_scale takes elliptical statistics (an anisotropic
    // model: tests/bsdf/test_two_scale_elliptical.cpp).
    o.alpha_from = AlphaFrom::measured;
    o.surface.gamma = 2.5;
    EXPECT_THROW(make_bsdf(o), Error);
    ModelOptions two = test::kc_options(ModelKind::two_scale, 0.05, 2.0, 4.0);
    two.surface.corr_length_v = 0.5;
    EXPECT_FALSE(make_bsdf(two)->isotropic());
}

// LV = LU (to 1e-10) reproduces the isotropic ggx_stats to 1e-9 for every alpha_from, whatever the lay angle.
TEST(Ggx, NearlyIsotropicEllipticalEqualsIsotropic) {
    for (AlphaFrom from : {AlphaFrom::measured, AlphaFrom::smoothed, AlphaFrom::kc_link}) {
        ModelOptions o = test::kc_options(ModelKind::ggx, 0.1, 1.5, 4.0);
        o.alpha_from = from;
        o.smoothing = 0.2;
        o.material = "Au";
        const auto iso = make_bsdf(o);
        o.surface.corr_length_v = 1.5 * (1 + 1e-10);
        o.surface.lay_angle = 70;
        const auto ell = make_bsdf(o);
        for (double ti : {0.0, 45.0, 80.0})
            for (double po : {0.0, 1.3, 3.0}) {
                const Vec3 wi = spherical_direction(ti * kDegree, 0.5), wo = spherical_direction(50 * kDegree, po);
                const double f = iso->eval(wi, wo, 550), p = iso->pdf(wi, wo, 550);
                EXPECT_NEAR(ell->eval(wi, wo, 550), f, 1e-9 * f) << to_string(from);
                EXPECT_NEAR(ell->pdf(wi, wo, 550), p, 1e-9 * p) << to_string(from);
            }
    }
}

// kc_link along u and v: the first-order lobe of an elliptical KC(3) surface at normal incidence, k^2 P-hat(2 k h_xy)
// with the elliptical KC PSD written here, is the anisotropic GGX D(h) of kc_link_alpha(LU), kc_link_alpha(LV) up to
// one constant factor.
TEST(Ggx, KcLinkIsTheEllipticalKcLobe) {
    const double lu = 1.2, lv = 0.3, lambda = 550, k = kTwoPi / (lambda * 1e-3);
    const GgxDistribution ggx(kc_link_alpha(lu, lambda), kc_link_alpha(lv, lambda));
    const auto psd = [&](double zu, double zv) {
        return lu * lv / kPi * std::pow(1 + lu * lu * zu * zu + lv * lv * zv * zv, -2.0);  // gamma 3, unit mass
    };
    double ratio0 = 0;
    for (double t : {0.0, 5.0, 20.0, 50.0, 80.0})
        for (double p : {0.0, 0.8, 1.6, 3.9}) {
            const Vec3 h = spherical_direction(t * kDegree, p);
            const double ratio = psd(2 * k * h.x, 2 * k * h.y) / ggx.D(h);
            if (ratio0 == 0) ratio0 = ratio;
            EXPECT_NEAR(ratio / ratio0, 1.0, 1e-12) << t << " " << p;
        }
}

// No NaN or Inf leaves eval, sample or pdf, whatever the inputs.
TEST(Models, ExtremeInputsStayFinite) {
    std::vector<ModelOptions> models;
    // Tiny and huge sigma and L (g from ~1e-14 to beyond the table's 1e6), a fractal gamma; the refit series with
    // Rayleigh-Rice Fresnel; GGX nearly smooth and very rough; two-scale.
    for (ModelKind m : {ModelKind::ghs, ModelKind::ghs_ssa})
        for (auto [sigma, length] : {std::pair{1e-5, 0.05}, std::pair{50.0, 500.0}})
            models.push_back(test::kc_options(m, sigma, length, 2.2));
    {
        auto o = test::kc_options(ModelKind::ghs, 0.5, 2.0, 3.0);
        o.method = GhsMethod::refit;
        o.fresnel = FresnelMode::rr;
        models.push_back(o);
        o = test::kc_options(ModelKind::two_scale, 0.3, 1.0, 3.0);
        o.cutoff_wavelengths = 5;
        models.push_back(o);
    }
    for (AlphaFrom from : {AlphaFrom::measured, AlphaFrom::kc_link}) {
        // Elliptical, stretched 100x (alpha_v 42 for measured) or 10x the other way (kc_link alpha_v 8e-4 at 100 nm).
        auto o = test::kc_options(ModelKind::ggx, 0.3, 1.0, 4.0);
        o.alpha_from = from;
        o.surface.corr_length_v = from == AlphaFrom::measured ? 0.01 : 10.0;
        o.surface.lay_angle = 45;
        models.push_back(o);
    }
    for (double alpha : {1e-4, 1.0}) {
        ModelOptions o;
        o.model = ModelKind::ggx;
        o.alpha_from = AlphaFrom::none;
        o.alpha = alpha;
        models.push_back(o);
    }
    const double eps = std::numeric_limits<double>::epsilon();
    const std::vector<Vec3> dirs{{0, 0, 1}, spherical_direction(89.999 * kDegree, 0.3), {1, 0, 0},
                                 normalize(Vec3(1, 0, -1e-9)), {0, 0, -1}, spherical_direction(45 * kDegree, 2)};
    for (const auto& o : models) {
        const auto bsdf = make_bsdf(o);
        for (double lambda : {100.0, 550.0, 1e5})
            for (const Vec3& wi : dirs) {
                for (const Vec3& wo : dirs) {
                    const double f = bsdf->eval(wi, wo, lambda), p = bsdf->pdf(wi, wo, lambda);
                    EXPECT_TRUE(std::isfinite(f) && f >= 0) << bsdf->name() << " f " << f;
                    EXPECT_TRUE(std::isfinite(p) && p >= 0) << bsdf->name() << " pdf " << p;
                }
                EXPECT_TRUE(std::isfinite(bsdf->delta_reflectance(wi, lambda)));
                for (double ul : {0.0, 0.5, 1 - eps})
                    for (double u : {0.0, 1 - eps, 0.5}) {
                        const auto s = bsdf->sample(wi, lambda, ul, Vec2(u, 1 - u));
                        if (!s) continue;
                        EXPECT_TRUE(std::isfinite(s->weight) && s->weight >= 0) << bsdf->name();
                        EXPECT_TRUE(std::isfinite(s->pdf) && s->pdf > 0) << bsdf->name();
                        EXPECT_GT(s->wo.z, 0) << bsdf->name();
                        EXPECT_NEAR(s->wo.length(), 1.0, 1e-9) << bsdf->name();
                    }
            }
    }
}

TEST(Models, EvalPacketEqualsPerWavelengthEvalAndPdf) {
    // The renderer's packet call (four wavelengths, f(wi, wo) and the density of drawing wi from wo) must give what
    // the one-wavelength interface gives, for every model, a real metal (dispersive Fresnel) and a roughness that
    // depends on the wavelength.
    std::vector<ModelOptions> models;
    for (ModelKind m : {ModelKind::ghs, ModelKind::ghs_ssa, ModelKind::two_scale}) {
        auto o = test::kc_options(m, 0.15, 4.0, 4.0);
        o.material = "Al";
        models.push_back(o);
    }
    for (AlphaFrom from : {AlphaFrom::none, AlphaFrom::kc_link}) {
        auto o = test::kc_options(ModelKind::ggx, 0.15, 4.0, 4.0);
        o.material = "Au";
        o.alpha_from = from;
        o.alpha = 0.2;
        models.push_back(o);
    }
    const WavelengthValues lambdas[] = {{380, 450, 600, 800}, {555.5, 555.5, 700, 361}};
    const std::vector<Vec3> dirs{{0, 0, 1}, spherical_direction(30 * kDegree, 0.4), spherical_direction(70 * kDegree, 2.5),
                                 spherical_direction(89.9 * kDegree, -1), {0, 0, -1}};
    for (const auto& o : models) {
        const auto bsdf = make_bsdf(o);
        for (const WavelengthValues& lambda : lambdas)
            for (const Vec3& wi : dirs)
                for (const Vec3& wo : dirs) {
                    WavelengthValues pdf{};
                    const WavelengthValues f = bsdf->eval_packet(wi, wo, lambda, &pdf);
                    EXPECT_EQ(bsdf->eval_packet(wi, wo, lambda, nullptr), f) << bsdf->name();
                    for (std::size_t k = 0; k < f.size(); ++k) {
                        const double f1 = bsdf->eval(wi, wo, lambda[k]), p1 = bsdf->pdf(wo, wi, lambda[k]);
                        EXPECT_NEAR(f[k], f1, 1e-12 * std::max(1.0, f1)) << bsdf->name() << " lambda " << lambda[k];
                        EXPECT_NEAR(pdf[k], p1, 1e-12 * std::max(1.0, p1)) << bsdf->name() << " lambda " << lambda[k];
                    }
                }
    }
}
