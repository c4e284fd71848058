// The Mitsuba BSDF plugins (bsdfs/*.cpp): a chi-square test of every sampler (the shared harness of tests/bsdf,
// transmission and several delta lobes included) and closed forms computed here independently: Fresnel reflection,
// refraction and total internal reflection of `dielectric`, the slab of `thindielectric`, the albedo of `plastic`
// (linear and nonlinear), `roughplastic` and `roughconductor` approaching their smooth limits, and glass in a
// uniform environment (energy conservation through the whole path tracer).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>

#include <fmt/format.h>

#include "bsdf/chi2_harness.hpp"
#include "render_test_util.hpp"
#include "surfscatter/io/image.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/material/fresnel.hpp"
#include "surfscatter/render/bsdfs/common.hpp"

using namespace surfscatter;
using namespace surfscatter::render;
using namespace surfscatter::render::test;
using surfscatter::bsdf::test::Chi2Subject;
using surfscatter::bsdf::test::DirectionSample;
namespace fs = std::filesystem;

namespace {

const SampledWavelengths kWavelengths = SampledWavelengths::sample_visible(0.37);
constexpr int kChi2Tests = 26;  // the chi-square tests below, for the Sidak correction
const double kAlpha = surfscatter::bsdf::test::sidak(0.01, kChi2Tests);

Vec3 direction(double theta_deg, double phi_deg = 30) { return spherical_direction(theta_deg * kDegree, phi_deg * kDegree); }

// Fresnel reflectance from n1 (light's side) to n2, written here from Born & Wolf independently of the library.
double fresnel_reference(double cos_i, double n1, double n2) {
    const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
    if (sin_t >= 1) return 1;
    const double cos_t = std::sqrt(1 - sin_t * sin_t);
    const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Hemispherical average 2 int F mu dmu by the midpoint rule on 200 000 points (independent of the library's).
double diffuse_fresnel_reference(double n1, double n2) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = (i + 0.5) / n;
        sum += fresnel_reference(mu, n1, n2) * mu;
    }
    return 2 * sum / n;
}

// The render material as a chi-square subject for viewer direction wo (hero wavelength densities).
Chi2Subject subject(const Material& m, const Vec3& wo, const ShadingPoint& sp = {}, bool full_sphere = false) {
    Chi2Subject s;
    s.full_sphere = full_sphere;
    s.sample = [&m, wo, sp](double ul, Vec2 u) -> std::optional<DirectionSample> {
        const auto r = m.sample(sp, wo, kWavelengths, ul, u);
        if (!r) return std::nullopt;
        const double weight = r->delta ? 0.0 : r->f[0] * std::abs(r->wi.z) / r->pdf[0];
        return DirectionSample{r->wi, r->pdf[0], weight, r->delta};
    };
    s.pdf = [&m, wo, sp](const Vec3& wi) {
        SampledSpectrum p;
        m.eval(sp, wi, wo, kWavelengths, &p);
        return p[0];
    };
    s.weight = [&m, wo, sp](const Vec3& wi) {
        SampledSpectrum p;
        const SampledSpectrum f = m.eval(sp, wi, wo, kWavelengths, &p);
        return p[0] > 0 ? f[0] * std::abs(wi.z) / p[0] : 0.0;
    };
    return s;
}

void expect_passes(const Chi2Subject& s, const std::string& name, long samples = 300000, int theta_bins = 30) {
    const auto r = surfscatter::bsdf::test::chi2_test(s, samples, s.full_sphere ? 2 * theta_bins : theta_bins, 60);
    std::printf("[chi2] %-46s %s\n", name.c_str(), r.summary().c_str());
    EXPECT_GT(r.p_value, kAlpha) << name << ": " << r.summary();
    EXPECT_LT(r.pdf_mismatch, 1e-6) << name;
    EXPECT_LT(r.weight_mismatch, 1e-6) << name;
    EXPECT_LT(r.expected_total, 1 + 1e-3) << name;
}

}  // namespace

TEST(Bsdfs, ContinuousSamplersPassChiSquare) {
    struct Case {
        const char* xml;
        double theta_o;
        bool full_sphere;
    };
    const Case cases[] = {
        {R"(<bsdf type="diffuse"/>)", 30, false},
        {R"(<bsdf type="roughconductor"><float name="alpha" value="0.3"/><string name="material" value="Au"/></bsdf>)", 20, false},
        {R"(<bsdf type="roughconductor"><float name="alpha" value="0.3"/></bsdf>)", 70, false},
        {R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>)", 45, false},
        {R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/>
            <boolean name="sample_visible" value="false"/></bsdf>)", 60, false},
        {R"(<bsdf type="roughdielectric"><float name="alpha" value="0.3"/></bsdf>)", 30, true},
        {R"(<bsdf type="roughdielectric"><float name="alpha" value="0.3"/></bsdf>)", 130, true},  // inside, beyond TIR
        {R"(<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/>
            <string name="int_ior" value="water"/></bsdf>)", 60, true},
        {R"(<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf>)", 160, true},
        {R"(<bsdf type="roughplastic"><float name="alpha" value="0.2"/></bsdf>)", 30, false},
        {R"(<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.3"/>
            <boolean name="nonlinear" value="true"/><rgb name="diffuse_reflectance" value="0.2, 0.5, 0.7"/></bsdf>)", 65, false},
        {R"(<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="diffuse"/>
            <bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha" value="0.2"/></bsdf></bsdf>)", 40, false},
        {R"(<bsdf type="twosided"><bsdf type="roughconductor"><float name="alpha" value="0.25"/></bsdf></bsdf>)", 140, true},
        {R"(<bsdf type="twosided"><bsdf type="diffuse"/><bsdf type="roughplastic"/></bsdf>)", 120, true},
        // Anisotropic: alpha_u along x (the shading frame's s), alpha_v along y.
        {R"(<bsdf type="roughconductor"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.4"/></bsdf>)", 50, false},
        {R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.35"/>
            <float name="alpha_v" value="0.08"/></bsdf>)", 60, false},
        {R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/>
            <float name="alpha_v" value="0.3"/><boolean name="sample_visible" value="false"/></bsdf>)", 40, false},
        {R"(<bsdf type="roughdielectric"><string name="distribution" value="ggx"/><float name="alpha_u" value="0.1"/>
            <float name="alpha_v" value="0.3"/></bsdf>)", 35, true},
    };
    for (const Case& c : cases) {
        const LoadedMaterial m = load_material(c.xml);
        const Vec3 wo = direction(c.theta_o);
        expect_passes(subject(*m.material, wo, {}, c.full_sphere), fmt::format("{} at {} deg", c.xml, c.theta_o));
    }
}

// alpha_u lies along the shading frame's x axis (s = dp/du): swapping alpha_u and alpha_v is the lobe turned by 90 deg
// about the normal; and the anisotropic lobe keeps the energy of a mirror's below 1 (its sampler's mean weight).
TEST(Bsdfs, AnisotropicAlphaFollowsTheShadingFrame) {
    for (const char* distribution : {"ggx", "beckmann"}) {
        const auto xml = [&](double u, double v) {
            return fmt::format(R"(<bsdf type="roughconductor"><string name="distribution" value="{}"/>
                <float name="alpha_u" value="{}"/><float name="alpha_v" value="{}"/><string name="material" value="Al"/></bsdf>)",
                               distribution, u, v);
        };
        const LoadedMaterial a = load_material(xml(0.08, 0.3)), b = load_material(xml(0.3, 0.08));
        const auto turn = [](const Vec3& w) { return Vec3(-w.y, w.x, w.z); };
        for (double ti : {10.0, 50.0})
            for (double po : {0.0, 70.0, 200.0}) {
                const Vec3 wi = direction(ti, 15), wo = direction(40, po);
                const double fa = a.material->eval({}, wi, wo, kWavelengths, nullptr)[0];
                const double fb = b.material->eval({}, turn(wi), turn(wo), kWavelengths, nullptr)[0];
                EXPECT_NEAR(fb, fa, 1e-12 * (1 + fa)) << distribution;
            }
        // Along u the lobe is narrow (alpha_u 0.08), across it wide: off-specular by 20 deg in the u-z plane it is
        // far below the same offset in the v-z plane (GGX: D ratio (1 + tan^2 10 deg / 0.3^2)^2 / (1 + tan^2 10 deg / 0.08^2)^2 = 0.053).
        const Vec3 wi(0, 0, 1);
        const double along_u = a.material->eval({}, wi, spherical_direction(20 * kDegree, 0), kWavelengths, nullptr)[0];
        const double along_v = a.material->eval({}, wi, spherical_direction(20 * kDegree, 0.5 * kPi), kWavelengths, nullptr)[0];
        EXPECT_LT(along_u, 0.1 * along_v) << distribution;
    }
    EXPECT_THROW(load_material(R"(<bsdf type="roughplastic"><float name="alpha_u" value="0.1"/><float name="alpha_v" value="0.3"/></bsdf>)"),
                 Error);
}

TEST(Bsdfs, SamplersWithDeltaLobesPassChiSquare) {
    const Vec3 wo = direction(40);
    const double f = fresnel_reference(wo.z, 1.000277, 1.49);
    {  // plastic: the delta lobe with probability F w / (F w + (1 - F)(1 - w)), w = 1 / (1 + 0.5)
        const LoadedMaterial m = load_material(R"(<bsdf type="plastic"/>)");
        Chi2Subject s = subject(*m.material, wo);
        const double w = 1 / 1.5;
        s.deltas.push_back({reflect_about_normal(wo), f * w / (f * w + (1 - f) * (1 - w))});
        expect_passes(s, "plastic at 40 deg");
    }
    {  // blendbsdf of a perfect mirror (probability 1 - weight) and a diffuse surface
        const LoadedMaterial m = load_material(
            R"(<bsdf type="blendbsdf"><float name="weight" value="0.3"/><bsdf type="conductor"/><bsdf type="diffuse"/></bsdf>)");
        Chi2Subject s = subject(*m.material, wo);
        s.deltas.push_back({reflect_about_normal(wo), 0.7});
        expect_passes(s, "blendbsdf mirror + diffuse");
    }
    {  // mask: straight through with probability 1 - opacity
        const LoadedMaterial m = load_material(R"(<bsdf type="mask"><float name="opacity" value="0.6"/>
            <bsdf type="roughconductor"><float name="alpha" value="0.2"/></bsdf></bsdf>)");
        Chi2Subject s = subject(*m.material, wo, {}, true);
        s.deltas.push_back({-wo, 0.4});
        expect_passes(s, "mask 0.6 over roughconductor");
    }
}

TEST(Bsdfs, PerturbedFramesPassChiSquare) {
    const fs::path dir = temp_dir("test_bsdfs");
    // A constant tilted normal map (RGB (0.7, 0.5, 0.85) -> n = normalize(0.4, 0, 0.7)) and a height ramp.
    io::Image normals(2, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 2; ++x) {
            normals.at(x, y, 0) = 0.7f;
            normals.at(x, y, 1) = 0.5f;
            normals.at(x, y, 2) = 0.85f;
        }
    io::write_exr(dir / "normals.exr", normals);
    io::Image ramp(8, 8, 1);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) ramp.at(x, y, 0) = static_cast<float>(0.1 * x + 0.05 * y);
    io::write_exr(dir / "ramp.exr", ramp);
    ShadingPoint sp;
    sp.uv = {0.4, 0.45};
    const LoadedMaterial normalmap = load_material(R"(<bsdf type="normalmap">
        <texture name="normalmap" type="bitmap"><boolean name="raw" value="true"/><string name="filename" value="normals.exr"/></texture>
        <bsdf type="roughconductor"><float name="alpha" value="0.3"/></bsdf></bsdf>)", dir / "scene.xml");
    expect_passes(subject(*normalmap.material, direction(30), sp), "normalmap over roughconductor");
    const LoadedMaterial bumpmap = load_material(R"(<bsdf type="bumpmap"><float name="scale" value="0.5"/>
        <texture type="bitmap"><boolean name="raw" value="true"/><string name="filename" value="ramp.exr"/></texture>
        <bsdf type="roughplastic"/></bsdf>)", dir / "scene.xml");
    expect_passes(subject(*bumpmap.material, direction(35), sp), "bumpmap over roughplastic");
}

TEST(Bsdfs, DielectricFresnelRefractionAndTotalInternalReflection) {
    const LoadedMaterial m = load_material(R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/>
        <float name="ext_ior" value="1"/></bsdf>)");
    // From outside at 30 degrees: chi-square of the two outcomes against Fresnel, Snell's direction, and the
    // transmitted radiance scaled by (1 / 1.5)^2.
    const Vec3 wo = direction(30);
    const double r = fresnel_reference(wo.z, 1.0, 1.5);
    const double sin_t = std::sin(30 * kDegree) / 1.5;
    const Vec3 refracted = spherical_direction(kPi - std::asin(sin_t), (30 + 180) * kDegree);
    Chi2Subject s = subject(*m.material, wo);
    s.deltas = {{reflect_about_normal(wo), r}, {refracted, 1 - r}};
    expect_passes(s, "dielectric from outside at 30 deg", 200000);
    const auto reflected = m.material->sample({}, wo, kWavelengths, 0.5 * r, {0.5, 0.5});
    const auto transmitted = m.material->sample({}, wo, kWavelengths, r + 0.5 * (1 - r), {0.5, 0.5});
    ASSERT_TRUE(reflected && transmitted);
    EXPECT_NEAR(reflected->f[0] / reflected->pdf[0], 1.0, 1e-12);
    EXPECT_NEAR(transmitted->f[0], (1 - r) / (1.5 * 1.5), 1e-12);
    EXPECT_NEAR(dot(transmitted->wi, refracted), 1.0, 1e-12);
    // From inside at 35 degrees (below the critical 41.8): refraction out, radiance scaled by 1.5^2.
    const Vec3 inside = direction(180 - 35);
    const double r_in = fresnel_reference(std::abs(inside.z), 1.5, 1.0);
    const auto out = m.material->sample({}, inside, kWavelengths, r_in + 0.5 * (1 - r_in), {0.5, 0.5});
    ASSERT_TRUE(out);
    EXPECT_NEAR(out->f[0], (1 - r_in) * 1.5 * 1.5, 1e-12);
    EXPECT_NEAR(std::sqrt(out->wi.x * out->wi.x + out->wi.y * out->wi.y), 1.5 * std::sin(35 * kDegree), 1e-12);
    // Beyond the critical angle everything is reflected with unit weight.
    const Vec3 grazing = direction(180 - 50);
    for (double u : {0.0, 0.5, 0.999999}) {
        const auto t = m.material->sample({}, grazing, kWavelengths, u, {0.5, 0.5});
        ASSERT_TRUE(t);
        EXPECT_NEAR(t->f[0], 1.0, 1e-15);
        EXPECT_NEAR(t->pdf[0], 1.0, 1e-15);
        EXPECT_NEAR(dot(t->wi, reflect_about_normal(grazing)), 1.0, 1e-12);
    }
}

TEST(Bsdfs, ThinDielectricSlabSumsItsInternalReflections) {
    const LoadedMaterial m = load_material(R"(<bsdf type="thindielectric"/>)");
    const Vec3 wo = direction(55);
    const double f = fresnel_reference(wo.z, 1.000277, 1.5046);
    // Geometric series of the reflections between the two faces: R = F + (1-F)^2 F / (1 - F^2).
    double reflected = f, transmitted = 0, inside = 1 - f;
    for (int bounce = 0; bounce < 200; ++bounce) {
        transmitted += inside * (1 - f);
        inside *= f;
        reflected += inside * (1 - f);
        inside *= f;
    }
    EXPECT_NEAR(reflected + transmitted, 1.0, 1e-12);
    Chi2Subject s = subject(*m.material, wo);
    s.deltas = {{reflect_about_normal(wo), reflected}, {-wo, transmitted}};
    expect_passes(s, "thindielectric at 55 deg", 200000);
}

TEST(Bsdfs, PlasticAlbedoMatchesItsClosedForm) {
    // Directional albedo = F(cos_o) (delta) + integral of the diffuse lobe; closed forms with F and Fdr from the
    // reference functions above: (1 - F) rho (linear) and (1 - F) rho (1 - Fdr) / (1 - rho Fdr) (nonlinear).
    const double eta = 1.49 / 1.000277, rho = 0.6;
    const double fdr = diffuse_fresnel_reference(1.49, 1.000277);
    for (bool nonlinear : {false, true}) {
        const LoadedMaterial m = load_material(fmt::format(
            R"(<bsdf type="plastic"><float name="diffuse_reflectance" value="{}"/><boolean name="nonlinear" value="{}"/></bsdf>)",
            rho, nonlinear ? "true" : "false"));
        for (double theta : {0.0, 45.0, 80.0}) {
            const Vec3 wo = direction(theta);
            const double f_o = fresnel_reference(wo.z, 1.000277, 1.49);
            // The diffuse lobe integrated by a 400 x 4 midpoint rule in cos^2 (it does not depend on phi).
            double integral = 0;
            const int n = 4000;
            for (int i = 0; i < n; ++i) {
                const double mu = std::sqrt((i + 0.5) / n);  // cos theta, uniform in cos^2
                const Vec3 wi(std::sqrt(1 - mu * mu), 0, mu);
                integral += m.material->eval({}, wi, wo, kWavelengths, nullptr)[0] * kPi / n;  // f mu dw = f pi d(mu^2)
            }
            const double expected = (1 - f_o) * (nonlinear ? rho * (1 - fdr) / (1 - rho * fdr) : rho);
            EXPECT_NEAR(integral, expected, 2e-4) << "nonlinear " << nonlinear << " theta " << theta << " eta " << eta;
            std::printf("[plastic] nonlinear=%d theta=%4.1f: albedo %.6f (delta %.6f + diffuse %.6f), closed form %.6f\n",
                        nonlinear, theta, f_o + integral, f_o, integral, f_o + expected);
        }
    }
}

namespace {

// Directional albedo by Monte Carlo with the material's own sampler: mean of f cos / pdf (delta: f / p).
std::pair<double, double> albedo_estimate(const Material& m, const Vec3& wo, long samples) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    double sum = 0, sum2 = 0;
    for (long i = 0; i < samples; ++i) {
        const double ul = uniform(rng);
        const Vec2 u(uniform(rng), uniform(rng));
        const auto s = m.sample({}, wo, kWavelengths, ul, u);
        double v = 0;
        if (s) v = s->delta ? s->f[0] / s->pdf[0] : s->f[0] * std::abs(s->wi.z) / s->pdf[0];
        sum += v;
        sum2 += v * v;
    }
    const double n = static_cast<double>(samples);
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

}  // namespace

TEST(Bsdfs, RoughPluginsApproachTheirSmoothLimits) {
    const Vec3 wo = direction(30);
    // roughplastic with a nearly smooth coating against plastic's closed-form albedo.
    const double f_o = fresnel_reference(wo.z, 1.000277, 1.49);
    const LoadedMaterial rough_plastic = load_material(
        R"(<bsdf type="roughplastic"><string name="distribution" value="ggx"/><float name="alpha" value="0.01"/></bsdf>)");
    const auto [plastic_albedo, plastic_error] = albedo_estimate(*rough_plastic.material, wo, 400000);
    const double smooth = f_o + (1 - f_o) * 0.5;
    std::printf("[roughplastic] alpha 0.01 at 30 deg: albedo %.5f +- %.5f, smooth plastic %.5f\n", plastic_albedo,
                plastic_error, smooth);
    EXPECT_NEAR(plastic_albedo, smooth, 0.005 + 4 * plastic_error);
    // roughconductor with a nearly smooth surface against the conductor Fresnel reflectance.
    const LoadedMaterial rough_metal = load_material(R"(<bsdf type="roughconductor"><string name="distribution" value="ggx"/>
        <float name="alpha" value="0.005"/><float name="eta" value="0.2"/><float name="k" value="3"/></bsdf>)");
    const auto [metal_albedo, metal_error] = albedo_estimate(*rough_metal.material, wo, 200000);
    const double expected = material::fresnel_conductor(wo.z, {0.2, 3.0});
    std::printf("[roughconductor] alpha 0.005 at 30 deg: albedo %.5f +- %.5f, Fresnel %.5f\n", metal_albedo, metal_error,
                expected);
    EXPECT_NEAR(metal_albedo, expected, 0.003 + 4 * metal_error);
    // roughdielectric: reflected plus transmitted energy (radiance scaling undone) close to 1 for small alpha.
    const LoadedMaterial rough_glass = load_material(R"(<bsdf type="roughdielectric"><string name="distribution" value="ggx"/>
        <float name="alpha" value="0.01"/><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>)");
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    double energy = 0;
    const long n = 200000;
    for (long i = 0; i < n; ++i) {
        const double ul = uniform(rng);
        const auto s = rough_glass.material->sample({}, wo, kWavelengths, ul, {uniform(rng), uniform(rng)});
        if (!s) continue;
        const double v = s->f[0] * std::abs(s->wi.z) / s->pdf[0];
        energy += s->wi.z > 0 ? v : v * 1.5 * 1.5;
    }
    std::printf("[roughdielectric] alpha 0.01 at 30 deg: R + T = %.5f\n", energy / n);
    EXPECT_NEAR(energy / n, 1.0, 0.01);
}

TEST(Bsdfs, GlassInAUniformEnvironmentIsInvisible) {
    // Lossless smooth glass (a sphere) and a thin pane in a constant environment: every path ends in the
    // environment with weight 1 (Fresnel and the eta^2 radiance scaling cancel), so every pixel is 1.
    for (const char* bsdf : {R"(<bsdf type="dielectric"/>)", R"(<bsdf type="thindielectric"/>)"}) {
        const std::string body = std::string(R"(<shape type="sphere"><float name="radius" value="1"/>)") + bsdf +
                                 R"(</shape><emitter type="constant"><spectrum name="radiance" value="360:1, 830:1"/></emitter>)";
        const std::string xml = scene_xml(body, "0, 0, 4", "0, 0, 0", 30, 12);
        const MeanY y = mean_y(render_string(xml, 32));
        std::printf("[furnace] %s: mean Y %.5f +- %.5f\n", bsdf, y.mean, y.standard_error);
        EXPECT_NEAR(y.mean, 1.0, 1e-3) << bsdf;
    }
}

TEST(Bsdfs, ConductorFresnelPacketInSinglePrecisionIsWithin1e6OfDouble) {
    // roughconductor and conductor evaluate Fresnel for the four wavelengths of a path at once in single precision;
    // its error against the double-precision reflectance of the same index (checked against an independent
    // formulation in tests/material) stays far below render noise.
    double max_error = 0;
    for (const char* name : {"Al", "Au", "Ag", "Cu", "Cr"}) {
        const material::Conductor metal = material::Conductor::from_name(name);
        const ConductorIor ior([&](double lambda) { return metal.ior(lambda); });
        for (double u = 0.005; u < 1; u += 0.01) {
            const SampledWavelengths w = SampledWavelengths::sample_visible(u);
            for (double c = 0; c <= 1.0; c += 1.0 / 64) {
                const SampledSpectrum r = ior.reflectance(c, w);
                for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
                    max_error = std::max(max_error, std::abs(r[i] - material::fresnel_conductor(c, ior.at(w.lambda[i]))));
            }
        }
    }
    std::printf("[fresnel packet] max |R_float - R_double| = %.2g\n", max_error);
    EXPECT_LT(max_error, 1e-6);
}
