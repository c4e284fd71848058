// Anisotropic GHS family (AnisotropicGhsBsdf, docs/MODELS.md "Anisotropic models"): SSA against the first-order
// closed form, LV = LU against the isotropic model, the higher orders against a 2-D FFT of the elliptical ACV, the
// azimuth tables against 2-D quadrature, samplers, albedo over every incidence azimuth, relabelling and rotation.
// Every reference is computed here (closed forms, FFTW, Gauss-Legendre over the visible disc).
#include <gtest/gtest.h>

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include <fmt/format.h>

#include "chi2_harness.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/anisotropic_ghs.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/core/paths.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

ModelOptions elliptical_kc(ModelKind model, double sigma, double lu, double lv, double gamma, double lay_deg) {
    ModelOptions o = test::kc_options(model, sigma, lu, gamma);
    o.surface.corr_length_v = lv;
    o.surface.lay_angle = lay_deg;
    return o;
}

const AnisotropicGhsBsdf& as_anisotropic(const Bsdf& b) { return dynamic_cast<const AnisotropicGhsBsdf&>(b); }

// The elliptical KC PSD (unit mass over the zeta plane), lay angle A in radians.
double elliptical_kc_psd(double lu, double lv, double gamma, double lay, Vec2 zeta) {
    const double zu = zeta.x * std::cos(lay) + zeta.y * std::sin(lay), zv = -zeta.x * std::sin(lay) + zeta.y * std::cos(lay);
    return (gamma - 1) * lu * lv / kTwoPi * std::pow(1 + lu * lu * zu * zu + lv * lv * zv * zv, -(gamma + 1) / 2);
}

// Integral over the visible disc of f(q, wo) d^2 q (q = i_xy + o_xy), polar about the specular point q = 0:
// azimuth by the midpoint rule (periodic), radius q = q_max(phi) t^3 (graded toward the lobe at q = 0) by 6-point
// Gauss-Legendre on `panels` panels of t in [0, 1].
template <class F>
double visible_disc_quadrature(const Vec3& wi, F f, int n_phi = 256, int panels = 40) {
    double sum = 0;
    for (int p = 0; p < n_phi; ++p) {
        const double phi = (p + 0.5) * kTwoPi / n_phi, ex = std::cos(phi), ey = std::sin(phi);
        const double b = ex * wi.x + ey * wi.y;
        const double q_max = b + std::sqrt(b * b + wi.z * wi.z);  // |q e - i_xy| = 1
        double radial = 0;
        for (int j = 0; j < panels; ++j)
            for (int a = 0; a < 6; ++a) {
                const double t = (j + 0.5 + 0.5 * test::detail::kGauss6X[a]) / panels;
                const double q = q_max * t * t * t, dq = 3 * q_max * t * t / panels * 0.5;
                const double ox = q * ex - wi.x, oy = q * ey - wi.y, z2 = 1 - ox * ox - oy * oy;
                if (!(z2 > 0)) continue;
                radial += test::detail::kGauss6W[a] * dq * q * f(Vec2(q * ex, q * ey), Vec3(ox, oy, std::sqrt(z2)));
            }
        sum += radial * kTwoPi / n_phi;
    }
    return sum;
}

Vec3 direction_deg(double theta, double phi) { return spherical_direction(theta * kDegree, phi * kDegree); }

}  // namespace

// Strict SSA is the first-order closed form F k^2 g_h P-hat(zeta), g_h = (k sigma_h (cos i + cos o))^2, with the
// elliptical KC PSD; the energy form is F N (1 - e^{-g}) k^2 P-hat with its own sigma and N.
TEST(AnisotropicGhs, SsaMatchesTheFirstOrderClosedForm) {
    const double sigma = 0.02, lu = 2.0, lv = 0.6, gamma = 2.5, lambda = 633.0, k = wavenumber(lambda);
    const auto gold = material::Conductor::from_name("Au");
    double worst_strict = 0, worst_energy = 0;
    for (double lay : {0.0, 30.0, 110.0})
        for (FresnelMode fresnel : {FresnelMode::incident, FresnelMode::half}) {
            ModelOptions o = elliptical_kc(ModelKind::ghs_ssa, sigma, lu, lv, gamma, lay);
            o.material = "Au";
            o.fresnel = fresnel;
            o.ssa_form = SsaForm::strict;
            const auto strict = make_bsdf(o);
            o.ssa_form = SsaForm::energy;
            o.surface.lay_angle = 110.0;  // the energy form at one lay angle (its tables take a second to build)
            const auto energy = make_bsdf(o);
            const auto& e = as_anisotropic(*energy);
            for (const Vec3& wi : {direction_deg(35, 20), direction_deg(70, -100)})
                for (double theta_o : {5.0, 30.0, 60.0, 80.0})
                    for (double phi_o : {-150.0, -60.0, 0.0, 45.0, 135.0}) {
                        const Vec3 wo = direction_deg(theta_o, phi_o);
                        const double p_hat = elliptical_kc_psd(lu, lv, gamma, lay * kDegree,
                                                               Vec2(k * (wi.x + wo.x), k * (wi.y + wo.y)));
                        const double f_fresnel = fresnel == FresnelMode::incident
                                                     ? gold.reflectance(wi.z, lambda)
                                                     : gold.reflectance(dot(wi, normalize(wi + wo)), lambda);
                        const double gh = std::pow(k * sigma * (wi.z + wo.z), 2);
                        const double want = f_fresnel * k * k * gh * p_hat;
                        worst_strict = std::max(worst_strict, std::abs(strict->eval(wi, wo, lambda) / want - 1));
                        const double g = std::pow(k * e.sigma(wi, lambda) * (wi.z + wo.z), 2);
                        const double p_hat_e = elliptical_kc_psd(lu, lv, gamma, 110.0 * kDegree,
                                                                 Vec2(k * (wi.x + wo.x), k * (wi.y + wo.y)));
                        const double want_e = f_fresnel * e.normalization(wi, lambda) * -std::expm1(-g) * k * k * p_hat_e;
                        worst_energy = std::max(worst_energy, std::abs(energy->eval(wi, wo, lambda) / want_e - 1));
                    }
        }
    EXPECT_LT(worst_strict, 1e-9);
    EXPECT_LT(worst_energy, 1e-9);
    fmt::print("SSA vs closed form: strict {:.2g}, energy {:.2g} relative\n", worst_strict, worst_energy);
}

// LV = LU through the factory is today's isotropic model, value for value; the anisotropic class itself at LV = LU
// agrees with GhsBsdf within its tables' accuracy.
TEST(AnisotropicGhs, EqualLengthsAreTheIsotropicModel) {
    const double lambda = 550.0;
    for (ModelKind model : {ModelKind::ghs, ModelKind::ghs_ssa}) {
        ModelOptions o = elliptical_kc(model, 0.1, 1.5, 1.5, 2.2, 37.0);
        const auto equal = make_bsdf(o);
        o.surface.corr_length_v = 0;
        const auto isotropic = make_bsdf(o);
        EXPECT_NE(dynamic_cast<const GhsBsdf*>(equal.get()), nullptr);
        for (const Vec3& wi : {direction_deg(0, 0), direction_deg(45, 30), direction_deg(80, 200)})
            for (const Vec3& wo : {direction_deg(10, 190), direction_deg(50, 210), direction_deg(70, 90)}) {
                EXPECT_NEAR(equal->eval(wi, wo, lambda), isotropic->eval(wi, wo, lambda),
                            1e-9 * isotropic->eval(wi, wo, lambda));
                EXPECT_NEAR(equal->pdf(wi, wo, lambda), isotropic->pdf(wi, wo, lambda), 1e-9 * isotropic->pdf(wi, wo, lambda));
            }
    }
    // The class at s = 1 against GhsBsdf: both tabulate sigma (5e-4) and N (1e-3) against their direct values.
    const auto kc = std::make_shared<surface::KCorrelation>(0.1, 1.5, 2.2);
    const auto core = std::make_shared<ExactScatterCore>(kc);
    const GhsBsdf iso(kc, core, material::Conductor::from_name("perfect"), GhsSettings{});
    const AnisotropicGhsBsdf aniso(std::make_shared<surface::EllipticalStatistics>(kc, 1.5, 0.6), core,
                                   material::Conductor::from_name("perfect"), GhsSettings{});
    double worst = 0;
    for (double theta_i : {0.0, 30.0, 65.0, 85.0})
        for (double theta_o : {0.0, 20.0, 60.0, 85.0})
            for (double phi_o : {0.0, 70.0, 180.0}) {
                const Vec3 wi = direction_deg(theta_i, 15), wo = direction_deg(theta_o, phi_o);
                worst = std::max(worst, std::abs(aniso.eval(wi, wo, lambda) / iso.eval(wi, wo, lambda) - 1));
            }
    EXPECT_LT(worst, 3e-3);
    fmt::print("anisotropic class at LV = LU vs GhsBsdf: {:.2g} relative\n", worst);
}

// The higher orders: S_g(zeta) = (2 pi)^-2 FT of e^{-g} (exp(g rho(x)) - 1), rho the elliptical Gaussian ACV
// exp(-(x_u/LU)^2 - (x_v/LV)^2), by FFTW on a 1024^2 grid over 16 um, against the stretched isotropic table.
TEST(AnisotropicGhs, HigherOrdersMatchATwoDimensionalFft) {
    const double lu = 1.0, lv = 0.4, lay = 30.0 * kDegree;
    const auto gaussian = std::make_shared<surface::GaussianAcv>(1.0, lu);
    const AnisotropicGhsBsdf bsdf(std::make_shared<surface::EllipticalStatistics>(gaussian, lv, lay),
                                  std::make_shared<ExactScatterCore>(gaussian), material::Conductor::from_name("perfect"),
                                  GhsSettings{});
    constexpr int n = 1024;
    const double extent = 16.0, dx = extent / n, dzeta = kTwoPi / extent;
    std::vector<double> acv(std::size_t(n) * n);
    fftw_complex* spectrum = fftw_alloc_complex(std::size_t(n) * (n / 2 + 1));
    double worst = 0;
    for (double g : {1.0, 5.0, 20.0}) {
        for (int iy = 0; iy < n; ++iy)
            for (int ix = 0; ix < n; ++ix) {
                const double x = (ix < n / 2 ? ix : ix - n) * dx, y = (iy < n / 2 ? iy : iy - n) * dx;
                const double u = x * std::cos(lay) + y * std::sin(lay), v = -x * std::sin(lay) + y * std::cos(lay);
                const double rho = std::exp(-(u / lu) * (u / lu) - (v / lv) * (v / lv));
                acv[std::size_t(iy) * n + ix] = std::exp(-g) * std::expm1(g * rho);
            }
        const fftw_plan plan = fftw_plan_dft_r2c_2d(n, n, acv.data(), spectrum, FFTW_ESTIMATE);
        fftw_execute(plan);
        fftw_destroy_plan(plan);
        const double peak = spectrum[0][0] * dx * dx / (kTwoPi * kTwoPi);
        const int reach = int(std::lround(std::sqrt(g)));  // the lobe widens like sqrt(g)
        for (const auto& [mx, my] : std::vector<std::pair<int, int>>{
                 {0, 0}, {2, 0}, {0, 2}, {3, 3}, {5, -2}, {1, -6}, {8, 1}, {4, 9}, {12, -5}}) {
            const int ix = mx * reach, iy = my * reach;
            const double want = spectrum[std::size_t((iy + n) % n) * (n / 2 + 1) + ix][0] * dx * dx / (kTwoPi * kTwoPi);
            if (want < 1e-4 * peak) continue;
            const double got = bsdf.lobe_density(g, Vec2(ix * dzeta, iy * dzeta));
            worst = std::max(worst, std::abs(got / want - 1));
            EXPECT_NEAR(got, want, 5e-3 * want) << "g " << g << " zeta index (" << ix << ", " << iy << ")";
        }
    }
    fftw_free(spectrum);
    fmt::print("stretched lobe vs 2-D FFT: {:.2g} relative\n", worst);
}

// sigma_rel^2 / sigma_h^2 = mass of P-hat over the visible disc and K = (1 - e^{-g0}) / (k^2 integral of the lobe),
// by Gauss-Legendre over the disc here.
struct EllipticalKc {
    double lu, lv, gamma, lay_deg;
};
GhsBsdf::Direct direct_by_quadrature(const AnisotropicGhsBsdf& a, const Vec3& wi, double lambda, double sigma_h,
                                     const EllipticalKc& kc, int n_phi = 256, int panels = 40) {
    const double k = wavenumber(lambda);
    const double mass = k * k * visible_disc_quadrature(wi, [&](Vec2 q, const Vec3&) {
        return elliptical_kc_psd(kc.lu, kc.lv, kc.gamma, kc.lay_deg * kDegree, q * k);
    }, n_phi, panels);
    const double sigma = sigma_h * std::sqrt(mass);
    const double lobe = k * k * visible_disc_quadrature(wi, [&](Vec2 q, const Vec3& wo) {
        return a.lobe_density(std::pow(k * sigma * (wi.z + wo.z), 2), q * k);
    }, n_phi, panels);
    return {sigma, -std::expm1(-std::pow(2 * k * sigma * wi.z, 2)) / lobe};
}

// The tables at incidence between the nodes (theta and azimuth) against that quadrature.
TEST(AnisotropicGhs, TablesMatchDirectQuadrature) {
    const double lambda = 3000.0, gamma = 2.5, sigma_h = 0.4;
    double worst_sigma = 0, worst_norm = 0, worst_direct = 0;
    for (const auto& [lu, lv, lay] : std::vector<std::tuple<double, double, double>>{{2.0, 0.5, 20.0}, {0.5, 2.0, -50.0}}) {
        const auto bsdf = make_bsdf(elliptical_kc(ModelKind::ghs, sigma_h, lu, lv, gamma, lay));
        const auto& a = as_anisotropic(*bsdf);
        for (double theta_i : {23.0, 61.0, 83.0})
            for (double phi_r : {7.0, 33.0, 52.0, 79.0, 98.0}) {
                const Vec3 wi = direction_deg(theta_i, lay + phi_r);
                const auto [sigma, norm] = direct_by_quadrature(a, wi, lambda, sigma_h, {lu, lv, gamma, lay});
                worst_sigma = std::max(worst_sigma, std::abs(a.sigma(wi, lambda) / sigma - 1));
                worst_norm = std::max(worst_norm, std::abs(a.normalization(wi, lambda) / norm - 1));
                const auto d = a.direct(wi, lambda);
                worst_direct = std::max({worst_direct, std::abs(d.sigma / sigma - 1), std::abs(d.norm / norm - 1)});
            }
    }
    EXPECT_LT(worst_sigma, 1e-3);
    EXPECT_LT(worst_norm, 3e-3);
    EXPECT_LT(worst_direct, 1e-4);
    fmt::print("tables vs quadrature: sigma {:.2g}, N {:.2g}; direct values {:.2g}\n", worst_sigma, worst_norm,
               worst_direct);
}

// Issue 34 item 8: the tabulated sigma_rel at every incidence azimuth (0.5 deg steps from the lay to its normal) up to
// grazing incidence, against the direct value (itself within 1e-4 of quadrature, next test), for photo-setup's brushed
// plate at 550 nm (the lobe ~1/15 of the disc, whose rim cuts it near the lay at grazing) and a wide lobe.
TEST(AnisotropicGhs, SigmaHoldsAtEveryAzimuthUpToGrazing) {
    double worst = 0, worst_theta = 0, worst_phi = 0;
    for (const auto& [lambda, sigma_h, kc] : std::vector<std::tuple<double, double, EllipticalKc>>{
             {550.0, 0.15, {4.0, 0.5, 4.0, 30.0}}, {3000.0, 0.4, {2.0, 0.5, 2.5, 20.0}}}) {
        const auto bsdf = make_bsdf(elliptical_kc(ModelKind::ghs, sigma_h, kc.lu, kc.lv, kc.gamma, kc.lay_deg));
        const auto& a = as_anisotropic(*bsdf);
        for (double theta_i : {30.0, 60.0, 80.0, 85.0, 89.0, 89.9})
            for (double phi_r = 0.0; phi_r <= 90.0; phi_r += 0.5) {
                const Vec3 wi = direction_deg(theta_i, kc.lay_deg + phi_r);
                const double error = std::abs(a.sigma(wi, lambda) / a.direct(wi, lambda).sigma - 1);
                if (error > worst) {
                    worst = error;
                    worst_theta = theta_i;
                    worst_phi = phi_r;
                }
            }
    }
    EXPECT_LT(worst, 1e-3);
    fmt::print("tabulated sigma against the direct value over every azimuth: worst {:.2g} at theta_i {}, phi_r {}\n",
               worst, worst_theta, worst_phi);
}

// The direct values where the ray-angle integral is graded (the specular point cos^2 theta_i / 2 from the horizon) and
// at normal incidence, for photo-setup's brushed plate (550 nm: a lobe ~1/15 of the disc) and a wide lobe (3000 nm),
// against the quadrature on a finer grid.
TEST(AnisotropicGhs, DirectValuesHoldAtGrazingIncidence) {
    double worst = 0;
    for (const auto& [lambda, sigma_h, kc] : std::vector<std::tuple<double, double, EllipticalKc>>{
             {550.0, 0.15, {4.0, 0.5, 4.0, 30.0}}, {3000.0, 0.4, {2.0, 0.5, 2.5, 20.0}}}) {
        const auto bsdf = make_bsdf(elliptical_kc(ModelKind::ghs, sigma_h, kc.lu, kc.lv, kc.gamma, kc.lay_deg));
        const auto& a = as_anisotropic(*bsdf);
        for (double theta_i : {0.0, 88.5, 89.7})
            for (double phi_r : {0.0, 33.0, 90.0}) {
                const Vec3 wi = direction_deg(theta_i, kc.lay_deg + phi_r);
                const auto reference = direct_by_quadrature(a, wi, lambda, sigma_h, kc, 1024, 80);
                const auto d = a.direct(wi, lambda);
                worst = std::max({worst, std::abs(d.sigma / reference.sigma - 1), std::abs(d.norm / reference.norm - 1)});
            }
    }
    EXPECT_LT(worst, 1e-4);
    fmt::print("direct values at grazing and normal incidence vs quadrature: {:.2g}\n", worst);
}

// Chi-square of the stretched-plane sampler in the lobe's own (|zeta|/k, wedge) cells.
TEST(AnisotropicGhs, SamplersPassChiSquare) {
    struct Case { ModelKind model; GhsMethod method; double lu, lv, lay, theta_i, phi_i, g; };
    const std::vector<Case> cases = {
        {ModelKind::ghs, GhsMethod::exact, 2.0, 0.6, 30.0, 40.0, 0.0, 1.0},
        {ModelKind::ghs, GhsMethod::exact, 0.8, 2.4, -60.0, 70.0, 100.0, 8.0},
        {ModelKind::ghs, GhsMethod::exact, 3.0, 0.5, 75.0, 15.0, 200.0, 0.2},
        {ModelKind::ghs, GhsMethod::refit, 2.0, 0.8, 10.0, 55.0, 45.0, 3.0},
        {ModelKind::ghs_ssa, GhsMethod::exact, 1.5, 0.4, 120.0, 60.0, -30.0, 0.5},
    };
    const double lambda = 550.0, alpha = test::sidak(0.01, int(cases.size()));
    for (const Case& c : cases) {
        ModelOptions o = elliptical_kc(c.model, test::sigma_for_g(c.g, lambda, c.theta_i), c.lu, c.lv, 2.5, c.lay);
        o.method = c.method;
        const auto bsdf = make_bsdf(o);
        const auto r = test::chi2_test_wedge(*bsdf, direction_deg(c.theta_i, c.phi_i), lambda, 200000);
        EXPECT_GT(r.p_value, alpha) << r.summary();
        EXPECT_LT(r.pdf_mismatch, 1e-9) << r.summary();
        EXPECT_LT(r.weight_mismatch, 1e-9) << r.summary();
        EXPECT_LE(r.expected_total, 1.0 + 1e-3) << r.summary();
    }
}

// GHS exact with renormalisation: albedo = R by K at every incidence azimuth (quadrature over the disc here).
TEST(AnisotropicGhs, AlbedoIsROverEveryIncidenceAzimuth) {
    const double lambda = 550.0;
    double worst = 0;
    for (const auto& [lu, lv, lay] : std::vector<std::tuple<double, double, double>>{{3.0, 1.0, 25.0}, {1.0, 4.0, -40.0}}) {
        const auto bsdf = make_bsdf(elliptical_kc(ModelKind::ghs, 0.08, lu, lv, 2.0, lay));
        for (double theta_i : {0.0, 40.0, 75.0})
            for (double phi_i = 0; phi_i < 180; phi_i += 15) {
                const Vec3 wi = direction_deg(theta_i, phi_i);
                const double albedo = visible_disc_quadrature(wi, [&](Vec2, const Vec3& wo) {
                    return bsdf->eval(wi, wo, lambda);
                }, 256, 60) + bsdf->delta_reflectance(wi, lambda);
                worst = std::max(worst, std::abs(albedo - 1));
                EXPECT_NEAR(albedo, 1.0, 5e-3) << "theta_i " << theta_i << " phi_i " << phi_i;
            }
    }
    fmt::print("albedo - R over incidence azimuths: {:.2g}\n", worst);
}

// A + 90 deg with LU and LV swapped is the same surface; a surface at lay angle A is the one at 0 rotated by A.
TEST(AnisotropicGhs, RelabellingAndRotation) {
    const double lambda = 550.0;
    const auto base = make_bsdf(elliptical_kc(ModelKind::ghs, 0.1, 2.0, 0.7, 2.3, 0.0));
    const auto rotated = make_bsdf(elliptical_kc(ModelKind::ghs, 0.1, 2.0, 0.7, 2.3, 35.0));
    const auto swapped = make_bsdf(elliptical_kc(ModelKind::ghs, 0.1, 0.7, 2.0, 2.3, 125.0));
    double worst_rotation = 0, worst_swap = 0;
    const double a = 35.0 * kDegree;
    auto rotate = [&](const Vec3& w) {  // by -A about the normal
        return Vec3(w.x * std::cos(a) + w.y * std::sin(a), -w.x * std::sin(a) + w.y * std::cos(a), w.z);
    };
    for (const Vec3& wi : {direction_deg(30, 10), direction_deg(65, 150), direction_deg(80, -70)})
        for (double theta_o : {5.0, 35.0, 70.0})
            for (double phi_o : {0.0, 60.0, 150.0, 250.0}) {
                const Vec3 wo = direction_deg(theta_o, phi_o);
                const double f = rotated->eval(wi, wo, lambda);
                if (f < 1e-6) continue;
                worst_rotation = std::max(worst_rotation, std::abs(base->eval(rotate(wi), rotate(wo), lambda) / f - 1));
                worst_swap = std::max(worst_swap, std::abs(swapped->eval(wi, wo, lambda) / f - 1));
            }
    EXPECT_LT(worst_rotation, 1e-3);
    EXPECT_LT(worst_swap, 5e-3);
    fmt::print("rotation {:.2g}, relabelling {:.2g} relative\n", worst_rotation, worst_swap);
}

// A new lay angle is a rotation of the local frame: its BSDF reads the incidence tables the first lay angle built
// (same file in the disk cache, none written) and gives the first one's values at the rotated directions (round-off).
TEST(AnisotropicGhs, NewLayAngleReusesTheTables) {
    const double lambda = 617.0;  // a wavelength no other test here builds first
    auto table_files = [] {
        std::size_t n = 0;
        for (const auto& e : std::filesystem::directory_iterator(cache_directory()))
            n += e.path().filename().string().starts_with("ghs-anisotropic-incidence-v4-");
        return n;
    };
    const auto base = make_bsdf(elliptical_kc(ModelKind::ghs, 0.08, 1.7, 0.6, 2.6, 0.0));
    const Vec3 wi0 = direction_deg(40, 25);
    ASSERT_GT(base->eval(wi0, direction_deg(35, 200), lambda), 0.0);  // builds (or loads) this wavelength's tables
    const std::size_t before = table_files();
    const double a = 50.0 * kDegree;
    const auto rotated = make_bsdf(elliptical_kc(ModelKind::ghs, 0.08, 1.7, 0.6, 2.6, 50.0));
    auto rotate = [&](const Vec3& w) {  // by -A about the normal: the lay frame of `rotated` onto that of `base`
        return Vec3(w.x * std::cos(a) + w.y * std::sin(a), -w.x * std::sin(a) + w.y * std::cos(a), w.z);
    };
    double worst = 0;
    for (const Vec3& wi : {direction_deg(20, 10), direction_deg(55, 150), direction_deg(75, -70)})
        for (double theta_o : {5.0, 40.0, 70.0})
            for (double phi_o : {0.0, 100.0, 190.0, 300.0}) {
                const Vec3 wo = direction_deg(theta_o, phi_o);
                const double f = rotated->eval(wi, wo, lambda), f0 = base->eval(rotate(wi), rotate(wo), lambda);
                ASSERT_GT(f0, 0.0);
                worst = std::max(worst, std::abs(f / f0 - 1));
            }
    EXPECT_EQ(table_files(), before);
    EXPECT_LT(worst, 1e-9);
    fmt::print("new lay angle: {} table files before and {} after, rotation {:.2g} relative\n", before, table_files(),
               worst);
}

// eval_packet is eval and the reverse pdf per wavelength; extreme directions and uniforms give finite values.
TEST(AnisotropicGhs, EvalPacketAndExtremeInputs) {
    const auto bsdf = make_bsdf(elliptical_kc(ModelKind::ghs, 0.05, 2.0, 0.5, 2.5, 20.0));
    const WavelengthValues lambdas{500.0, 505.0, 510.0, 515.0};
    for (const Vec3& wi : {direction_deg(0, 0), direction_deg(45, 60), direction_deg(89.99, 200)})
        for (const Vec3& wo : {direction_deg(0, 0), direction_deg(30, 250), direction_deg(89.99, 10)}) {
            WavelengthValues pdf{};
            const WavelengthValues f = bsdf->eval_packet(wi, wo, lambdas, &pdf);
            for (std::size_t j = 0; j < f.size(); ++j) {
                EXPECT_NEAR(f[j], bsdf->eval(wi, wo, lambdas[j]), 1e-12 * bsdf->eval(wi, wo, lambdas[j]));
                EXPECT_NEAR(pdf[j], bsdf->pdf(wo, wi, lambdas[j]), 1e-12 * bsdf->pdf(wo, wi, lambdas[j]));
            }
        }
    const Vec3 below(0.3, 0.1, -0.9487);
    EXPECT_EQ(bsdf->eval(below, direction_deg(30, 0), 500.0), 0.0);
    EXPECT_EQ(bsdf->pdf(direction_deg(30, 0), below, 500.0), 0.0);
    EXPECT_FALSE(bsdf->sample(below, 500.0, 0.5, Vec2(0.5, 0.5)));
    for (double theta : {0.0, 60.0, 89.999})
        for (double u : {0.0, 0.5, std::nextafter(1.0, 0.0)}) {
            const Vec3 wi = direction_deg(theta, 130);
            const auto s = bsdf->sample(wi, 500.0, u, Vec2(u, 1.0 - u));
            if (!s) continue;
            EXPECT_TRUE(std::isfinite(s->weight) && std::isfinite(s->pdf) && s->pdf > 0) << theta << " " << u;
            EXPECT_TRUE(std::isfinite(bsdf->eval(wi, s->wo, 500.0)));
        }
}
