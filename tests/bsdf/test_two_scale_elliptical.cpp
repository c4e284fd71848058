// Two-scale model on elliptical statistics (docs/MODELS.md "Two-scale on elliptical statistics"): the split on the
// ellipse |(zeta_u, s zeta_v)| = zeta_c min(1, s) against 2-D quadrature of the elliptical PSD (macro alpha_u, alpha_v
// and the lay from the low-pass slope covariance, the micro variance; the circle cut |zeta| = zeta_c measured against
// it), the micro lobe's first order against the cut PSD and its higher orders against a 2-D FFT of the cut ACV's
// powers, LV = LU against the isotropic model, samplers, the albedo over incidence azimuths, relabelling.
// Every reference is computed here (closed-form PSDs, Gauss-Legendre, FFTW).
#include <gtest/gtest.h>

#include <fftw3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "chi2_harness.hpp"
#include "model_fixtures.hpp"
#include "surfscatter/bsdf/anisotropic_ghs.hpp"
#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/bsdf/wedge_sampling.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/radial_statistics.hpp"

using namespace surfscatter;
using namespace surfscatter::bsdf;

namespace {

struct Surface {
    double sigma, lu, lv, gamma, lay_deg, n;  // KC; n the cutoff in wavelengths at 550 nm
};

ModelOptions two_scale_options(const Surface& s) {
    ModelOptions o = test::kc_options(ModelKind::two_scale, s.sigma, s.lu, s.gamma);
    o.surface.corr_length_v = s.lv;
    o.surface.lay_angle = s.lay_deg;
    o.cutoff_wavelengths = s.n;
    o.material = "perfect";
    return o;
}

const TwoScaleBsdf& as_two_scale(const Bsdf& b) { return dynamic_cast<const TwoScaleBsdf&>(b); }
const AnisotropicGhsBsdf& micro_of(const Bsdf& b) {
    return dynamic_cast<const AnisotropicGhsBsdf&>(as_two_scale(b).micro());
}

Vec2 to_lay(Vec2 xy, double lay) {
    return {xy.x * std::cos(lay) + xy.y * std::sin(lay), -xy.x * std::sin(lay) + xy.y * std::cos(lay)};
}

// The elliptical KC PSD of unit mass, written out: (gamma - 1) LU LV / (2 pi) (1 + LU^2 zeta_u^2 + LV^2 zeta_v^2)^-(gamma+1)/2.
double kc_psd(const Surface& s, Vec2 zeta) {
    const Vec2 uv = to_lay(zeta, s.lay_deg * kDegree);
    return (s.gamma - 1) * s.lu * s.lv / kTwoPi *
           std::pow(1 + s.lu * s.lu * uv.x * uv.x + s.lv * s.lv * uv.y * uv.y, -(s.gamma + 1) / 2);
}

double zeta_cut(const Surface& s) { return kTwoPi / (s.n * kTwoScaleReferenceWavelength * 1e-3); }

// Distance from 0 to the boundary of the low-pass region along the unit vector e (local frame): the ellipse
// LU^2 zeta_u^2 + LV^2 zeta_v^2 = min(LU, LV)^2 zeta_c^2, or the circle zeta_c.
double boundary(const Surface& s, Vec2 e, bool circle) {
    if (circle) return zeta_cut(s);
    const Vec2 uv = to_lay(e, s.lay_deg * kDegree);
    return std::min(s.lu, s.lv) * zeta_cut(s) / std::sqrt(s.lu * s.lu * uv.x * uv.x + s.lv * s.lv * uv.y * uv.y);
}

// Mass and slope covariance (local frame) of the unit PSD over the low-pass region: polar coordinates about 0, the
// azimuth by the midpoint rule, the radius by 8-point Gauss-Legendre on panels graded geometrically toward 0.
struct LowPass {
    double mass = 0, xx = 0, xy = 0, yy = 0;
};
LowPass low_pass_moments(const Surface& s, bool circle) {
    std::vector<double> x, w;
    math::gauss_legendre(8, x, w);
    LowPass m;
    constexpr int n_phi = 720, panels = 60;
    for (int p = 0; p < n_phi; ++p) {
        const double phi = (p + 0.5) * kTwoPi / n_phi;
        const Vec2 e(std::cos(phi), std::sin(phi));
        const double t_max = boundary(s, e, circle);
        for (int j = 0; j < panels; ++j) {
            const double a = t_max * std::pow(1e-6, 1.0 - double(j) / panels) * (j == 0 ? 0.0 : 1.0);
            const double b = t_max * std::pow(1e-6, 1.0 - double(j + 1) / panels);
            for (std::size_t i = 0; i < x.size(); ++i) {
                const double t = 0.5 * (a + b) + 0.5 * (b - a) * x[i];
                const double weight = 0.5 * (b - a) * w[i] * t * kTwoPi / n_phi * kc_psd(s, e * t);
                m.mass += weight;
                m.xx += weight * t * t * e.x * e.x;
                m.xy += weight * t * t * e.x * e.y;
                m.yy += weight * t * t * e.y * e.y;
            }
        }
    }
    return m;
}

Vec3 direction_deg(double theta, double phi) { return spherical_direction(theta * kDegree, phi * kDegree); }

const std::vector<Surface> kSurfaces = {
    {0.1, 2.0, 0.5, 2.5, 30.0, 20.0},
    {0.05, 0.8, 3.0, 4.0, -70.0, 50.0},
};

}  // namespace

// alpha_u^2 / 2 and alpha_v^2 / 2 are the eigenvalues of the low-pass part's slope covariance, u along the lay angle,
// and sigma_micro^2 = sigma^2 (1 - mass inside the ellipse). The circle cut |zeta| = zeta_c, by the same quadrature,
// is what the ellipse replaces: its alphas and micro sigma are printed against the ellipse's.
TEST(TwoScaleElliptical, SplitMatchesTwoDimensionalQuadrature) {
    std::vector<Surface> surfaces = kSurfaces;
    surfaces.push_back({0.1, 2.0, 1.4, 3.0, 10.0, 100.0});  // a mild anisotropy at the default cutoff
    double worst = 0;
    for (const Surface& s : surfaces) {
        const auto bsdf = make_bsdf(two_scale_options(s));
        const Vec2 alpha = as_two_scale(*bsdf).macro_alpha_uv();
        const LowPass m = low_pass_moments(s, false);
        const double sigma2 = s.sigma * s.sigma;
        const double trace = m.xx + m.yy, root = std::sqrt(0.25 * (m.xx - m.yy) * (m.xx - m.yy) + m.xy * m.xy);
        const double big = sigma2 * (0.5 * trace + root), small = sigma2 * (0.5 * trace - root);
        const double lay = s.lay_deg * kDegree, cu = std::cos(lay), su = std::sin(lay);
        const double uu = sigma2 * (m.xx * cu * cu + 2 * m.xy * cu * su + m.yy * su * su);
        const double uv = sigma2 * ((m.yy - m.xx) * cu * su + m.xy * (cu * cu - su * su));
        EXPECT_NEAR(0.5 * alpha.x * alpha.x, uu, 1e-9 * uu);
        EXPECT_NEAR(uv, 0.0, 1e-9 * big);
        EXPECT_NEAR(0.5 * std::max(alpha.x * alpha.x, alpha.y * alpha.y), big, 1e-9 * big);
        EXPECT_NEAR(0.5 * std::min(alpha.x * alpha.x, alpha.y * alpha.y), small, 1e-9 * small);
        const double sigma_micro = s.sigma * std::sqrt(1 - m.mass);
        EXPECT_NEAR(micro_of(*bsdf).statistics().sigma_h(), sigma_micro, 1e-9 * sigma_micro);
        worst = std::max({worst, std::abs(0.5 * alpha.x * alpha.x / uu - 1), std::abs(uv / big),
                          std::abs(micro_of(*bsdf).statistics().sigma_h() / sigma_micro - 1)});

        const LowPass c = low_pass_moments(s, true);
        const double cuu = sigma2 * (c.xx * cu * cu + 2 * c.xy * cu * su + c.yy * su * su);
        const double cvv = sigma2 * (c.xx * su * su - 2 * c.xy * cu * su + c.yy * cu * cu);
        fmt::print("LU {} LV {} gamma {} N {}: ellipse alpha_u {:.5f} alpha_v {:.5f} sigma_micro {:.5f} um; circle "
                   "alpha_u {:.5f} alpha_v {:.5f} sigma_micro {:.5f} um\n", s.lu, s.lv, s.gamma, s.n, alpha.x, alpha.y,
                   sigma_micro, std::sqrt(2 * cuu), std::sqrt(2 * cvv), s.sigma * std::sqrt(1 - c.mass));
    }
    fmt::print("split vs 2-D quadrature: {:.2g} relative\n", worst);
}

// At g -> 0 the lobe is g e^{-g} P-hat_HP: zero inside the ellipse, the elliptical KC PSD over 1 - F_c outside
// (F_c the mass inside, by quadrature here); the orders m >= 2 are continuous and fill the hole.
TEST(TwoScaleElliptical, MicroFirstOrderIsTheCutPsd) {
    const double g = 1e-8;
    for (const Surface& s : kSurfaces) {
        const auto bsdf = make_bsdf(two_scale_options(s));
        const auto& micro = micro_of(*bsdf);
        const double outside = 1 - low_pass_moments(s, false).mass;
        double worst = 0, worst_hole = 0;
        for (double phi = 5; phi < 360; phi += 20) {
            const Vec2 e(std::cos(phi * kDegree), std::sin(phi * kDegree));
            const double edge = boundary(s, e, false);
            for (double t : {1.0001, 1.01, 1.3, 2.0, 5.0, 20.0}) {
                const double want = g * std::exp(-g) * kc_psd(s, e * (t * edge)) / outside;
                const double got = micro.lobe_density(g, e * (t * edge));
                worst = std::max(worst, std::abs(got / want - 1));
            }
            for (double t : {0.1, 0.5, 0.9999}) {
                const double uncut = g * kc_psd(s, e * (t * edge)) / outside;
                worst_hole = std::max(worst_hole, micro.lobe_density(g, e * (t * edge)) / uncut);
            }
        }
        EXPECT_LT(worst, 1e-6);
        EXPECT_LT(worst_hole, 1e-6);
        fmt::print("first order outside the ellipse: {:.2g} relative; inside, lobe / uncut first order <= {:.2g}\n",
                   worst, worst_hole);
    }
}

// The orders m >= 2: S_g - g e^{-g} P-hat_HP = (2 pi)^-2 FT of e^{-g} (exp(g rho) - 1 - g rho), rho the ACV of the
// cut elliptical Gaussian PSD (sampled on the zeta grid, the hole included, and transformed back by FFTW: 2048^2 over
// 64 um), against the stretched isotropic sharp-cut table.
TEST(TwoScaleElliptical, MicroHigherOrdersMatchATwoDimensionalFft) {
    const double lu = 1.0, lv = 0.4, lay = 30.0 * kDegree, zeta_c = 3.0;
    const auto gaussian = std::make_shared<surface::GaussianAcv>(1.0, lu);
    const auto split = surface::split_elliptical_psd(surface::EllipticalStatistics(gaussian, lv, lay), zeta_c);
    const AnisotropicGhsBsdf micro(split.micro, std::make_shared<ExactScatterCore>(split.micro->radial_ptr()),
                                   material::Conductor::perfect(), GhsSettings{});
    constexpr int n = 2048, half = n / 2 + 1;
    const double extent = 64.0, dx = extent / n, dzeta = kTwoPi / extent;
    const double cut = zeta_c * std::min(1.0, lv / lu);
    auto cut_psd = [&](double zx, double zy) {  // unit-mass elliptical Gaussian PSD outside the ellipse, not renormalised
        const Vec2 uv = to_lay({zx, zy}, lay);
        if (uv.x * uv.x + (lv / lu) * (lv / lu) * uv.y * uv.y <= cut * cut) return 0.0;
        return lu * lv / (4 * kPi) * std::exp(-0.25 * (lu * lu * uv.x * uv.x + lv * lv * uv.y * uv.y));
    };
    // The grid's samples: cell means where the ellipse crosses the cell (16^2 points), so that the discrete
    // convolutions see the hole's area, not its lattice points.
    auto cell_psd = [&](double zx, double zy) {
        bool inside = false, outside = false;
        for (double cx : {-0.5, 0.5})
            for (double cy : {-0.5, 0.5}) (cut_psd(zx + cx * dzeta, zy + cy * dzeta) == 0.0 ? inside : outside) = true;
        if (!(inside && outside)) return cut_psd(zx, zy);
        double sum = 0;
        for (int a = 0; a < 16; ++a)
            for (int b = 0; b < 16; ++b)
                sum += cut_psd(zx + ((a + 0.5) / 16 - 0.5) * dzeta, zy + ((b + 0.5) / 16 - 0.5) * dzeta);
        return sum / 256;
    };
    fftw_complex* spectrum = fftw_alloc_complex(std::size_t(n) * half);
    std::vector<double> acv(std::size_t(n) * n);
    double mass = 0;
    for (int iy = 0; iy < n; ++iy)
        for (int ix = 0; ix < half; ++ix) {
            const double p = cell_psd(ix * dzeta, (iy < n / 2 ? iy : iy - n) * dzeta);
            spectrum[std::size_t(iy) * half + ix][0] = p;
            spectrum[std::size_t(iy) * half + ix][1] = 0.0;
            mass += (ix == 0 || ix == n / 2 ? 1.0 : 2.0) * p * dzeta * dzeta;
        }
    const fftw_plan back = fftw_plan_dft_c2r_2d(n, n, spectrum, acv.data(), FFTW_ESTIMATE);
    fftw_execute(back);
    fftw_destroy_plan(back);
    for (double& r : acv) r *= dzeta * dzeta / mass;  // rho, rho(0) = 1
    std::vector<double> powers(acv.size());
    double worst = 0;
    for (double g : {1.0, 5.0, 20.0}) {
        for (std::size_t j = 0; j < acv.size(); ++j) powers[j] = std::exp(-g) * (std::expm1(g * acv[j]) - g * acv[j]);
        const fftw_plan forward = fftw_plan_dft_r2c_2d(n, n, powers.data(), spectrum, FFTW_ESTIMATE);
        fftw_execute(forward);
        fftw_destroy_plan(forward);
        const double scale = dx * dx / (kTwoPi * kTwoPi), peak = spectrum[0][0] * scale;
        for (int ix = 0; ix < 160; ix += 7)
            for (int iy = -150; iy < 150; iy += 11) {
                const double want = spectrum[std::size_t((iy + n) % n) * half + ix][0] * scale;
                if (want < 1e-4 * peak) continue;
                const Vec2 zeta(ix * dzeta, iy * dzeta);
                const double first = g * std::exp(-g) * cut_psd(zeta.x, zeta.y) / mass;
                const double got = micro.lobe_density(g, zeta) - first;
                worst = std::max(worst, std::abs(got / want - 1));
                EXPECT_NEAR(got, want, 5e-3 * want) << "g " << g << " zeta index (" << ix << ", " << iy << ")";
            }
    }
    fftw_free(spectrum);
    fmt::print("orders m >= 2 of the cut stretched lobe vs 2-D FFT: {:.2g} relative\n", worst);
}

// LV = LU through the factory is today's isotropic two_scale, value for value; the elliptical construction at
// s = 1 (ellipse = circle) agrees with it within the anisotropic GHS tables' accuracy.
TEST(TwoScaleElliptical, EqualLengthsAreTheIsotropicModel) {
    const double lambda = 550.0;
    const Surface s{0.08, 1.5, 1.5, 3.0, 37.0, 30.0};
    ModelOptions o = two_scale_options(s);
    const auto equal = make_bsdf(o);
    o.surface.corr_length_v = 0;
    o.surface.lay_angle = 0;
    const auto isotropic = make_bsdf(o);
    EXPECT_NE(dynamic_cast<const GhsBsdf*>(&as_two_scale(*equal).micro()), nullptr);
    const auto split = surface::split_elliptical_psd(
        surface::EllipticalStatistics(std::make_shared<surface::KCorrelation>(s.sigma, s.lu, s.gamma), s.lu, 0.6),
        zeta_cut(s));
    GhsSettings settings;
    settings.name = "two_scale_micro";
    const Vec2 alpha(std::sqrt(2 * split.slope_variances_lay.x), std::sqrt(2 * split.slope_variances_lay.y));
    const TwoScaleBsdf stretched(
        material::Conductor::perfect(), MacroNdf::ggx, alpha, 0.6,
        std::make_unique<AnisotropicGhsBsdf>(split.micro, std::make_shared<ExactScatterCore>(split.micro->radial_ptr()),
                                             material::Conductor::perfect(), settings));
    EXPECT_NEAR(alpha.x, as_two_scale(*isotropic).macro_alpha(), 1e-12 * alpha.x);
    EXPECT_NEAR(alpha.y, alpha.x, 1e-12 * alpha.x);
    double worst = 0;
    for (const Vec3& wi : {direction_deg(0, 0), direction_deg(45, 30), direction_deg(80, 200)})
        for (double theta_o : {0.0, 10.0, 44.0, 50.0, 70.0})
            for (double phi_o : {0.0, 100.0, 210.0}) {
                const Vec3 wo = direction_deg(theta_o, phi_o);
                const double f = isotropic->eval(wi, wo, lambda);
                EXPECT_NEAR(equal->eval(wi, wo, lambda), f, 1e-9 * f);
                EXPECT_NEAR(equal->pdf(wi, wo, lambda), isotropic->pdf(wi, wo, lambda), 1e-9 * isotropic->pdf(wi, wo, lambda));
                worst = std::max(worst, std::abs(stretched.eval(wi, wo, lambda) / f - 1));
            }
    EXPECT_LT(worst, 3e-3);
    fmt::print("elliptical two_scale at LV = LU vs isotropic: {:.2g} relative\n", worst);
}

// Chi-square of the mixture sampler (macro NDF or stretched micro lobe) in the lobe's own cells, edges at the hole's
// semi-axes.
TEST(TwoScaleElliptical, SamplersPassChiSquare) {
    struct Case { Surface surface; MacroNdf ndf; double theta_i, phi_i; };
    const std::vector<Case> cases = {
        {kSurfaces[0], MacroNdf::ggx, 40.0, 10.0},
        {kSurfaces[1], MacroNdf::ggx, 70.0, 100.0},
        {kSurfaces[0], MacroNdf::beckmann, 15.0, 200.0},
    };
    const double lambda = 550.0, level = test::sidak(0.01, int(cases.size()));
    for (const Case& c : cases) {
        ModelOptions o = two_scale_options(c.surface);
        o.macro_ndf = c.ndf;
        const auto bsdf = make_bsdf(o);
        const double k = wavenumber(lambda), cut = zeta_cut(c.surface) * std::min(1.0, c.surface.lv / c.surface.lu);
        const double stretch = c.surface.lv / c.surface.lu;
        const auto r = test::chi2_test_wedge(*bsdf, direction_deg(c.theta_i, c.phi_i), lambda, 200000,
                                             {cut / k, cut / (stretch * k)});
        EXPECT_GT(r.p_value, level) << r.summary();
        EXPECT_LT(r.pdf_mismatch, 1e-6) << r.summary();
        EXPECT_LT(r.weight_mismatch, 1e-6) << r.summary();
        EXPECT_LE(r.expected_total, 1.0 + 1e-3) << r.summary();
    }
}

namespace {

// Integral of f(wo) over the visible disc d^2 q (q = i_xy + o_xy), polar about the specular point: azimuth by the
// midpoint rule; each ray split at the micro lobe's hole (q = boundary / k) and 6-point Gauss-Legendre on 40 panels per
// piece, graded as t^3 toward the specular point and toward the hole's edge from both sides.
template <class F>
double disc_quadrature(const Surface& s, const Vec3& wi, double k, F f) {
    constexpr int n_phi = 256, panels = 40;
    double sum = 0;
    for (int p = 0; p < n_phi; ++p) {
        const double phi = (p + 0.5) * kTwoPi / n_phi;
        const Vec2 e(std::cos(phi), std::sin(phi));
        const double b = e.x * wi.x + e.y * wi.y, q_max = b + std::sqrt(b * b + wi.z * wi.z);
        const double q_hole = std::min(boundary(s, e, false) / k, q_max);
        // (start, length, direction): q = start + direction length t^3, t in [0, 1]
        const std::array<std::array<double, 3>, 3> pieces = {{{0.0, 0.5 * q_hole, 1.0}, {q_hole, 0.5 * q_hole, -1.0},
                                                              {q_hole, q_max - q_hole, 1.0}}};
        double radial = 0;
        for (const auto& [start, length, direction] : pieces)
            for (int j = 0; j < panels; ++j)
                for (int a = 0; a < 6; ++a) {
                    const double t = (j + 0.5 + 0.5 * test::detail::kGauss6X[a]) / panels;
                    const double q = start + direction * length * t * t * t, dq = 3 * length * t * t / panels * 0.5;
                    const double ox = q * e.x - wi.x, oy = q * e.y - wi.y, z2 = 1 - ox * ox - oy * oy;
                    if (!(z2 > 0)) continue;
                    radial += test::detail::kGauss6W[a] * dq * q * f(Vec3(ox, oy, std::sqrt(z2)));
                }
        sum += radial * kTwoPi / n_phi;
    }
    return sum;
}

}  // namespace

// Perfect conductor: the micro lobe alone carries R = 1 (its K, whose cubature does not know the elliptical hole,
// against quadrature that splits every ray there) and the two-scale albedo is at most R, at incidence azimuths every
// 30 deg.
TEST(TwoScaleElliptical, AlbedoAtMostROverEveryIncidenceAzimuth) {
    const double lambda = 550.0, k = wavenumber(lambda);
    double worst_micro = 0, highest = 0, lowest = 2;
    for (const Surface& s : kSurfaces) {
        const auto bsdf = make_bsdf(two_scale_options(s));
        const Bsdf& micro = as_two_scale(*bsdf).micro();
        for (double theta_i : {0.0, 40.0, 75.0})
            for (double phi_i = 0; phi_i < 360; phi_i += 30) {
                const Vec3 wi = direction_deg(theta_i, phi_i);
                const double micro_albedo =
                    disc_quadrature(s, wi, k, [&](const Vec3& wo) { return micro.eval(wi, wo, lambda); }) +
                    micro.delta_reflectance(wi, lambda);
                const double albedo = disc_quadrature(s, wi, k, [&](const Vec3& wo) { return bsdf->eval(wi, wo, lambda); });
                worst_micro = std::max(worst_micro, std::abs(micro_albedo - 1));
                highest = std::max(highest, albedo);
                lowest = std::min(lowest, albedo);
                EXPECT_NEAR(micro_albedo, 1.0, 2e-4) << "theta_i " << theta_i << " phi_i " << phi_i;
                EXPECT_LE(albedo, 1.005) << "theta_i " << theta_i << " phi_i " << phi_i;
            }
    }
    fmt::print("micro albedo - R: {:.2g}; two-scale albedo {:.4f} .. {:.4f}\n", worst_micro, lowest, highest);
}

// A + 90 deg with LU and LV swapped is the same surface: the same macro alphas swapped, the same BRDF.
TEST(TwoScaleElliptical, RelabellingIsTheSameSurface) {
    const double lambda = 550.0;
    const Surface s = kSurfaces[0];
    const auto base = make_bsdf(two_scale_options(s));
    const auto swapped = make_bsdf(two_scale_options({s.sigma, s.lv, s.lu, s.gamma, s.lay_deg + 90.0, s.n}));
    const Vec2 a = as_two_scale(*base).macro_alpha_uv(), b = as_two_scale(*swapped).macro_alpha_uv();
    EXPECT_NEAR(b.x, a.y, 1e-9 * a.y);
    EXPECT_NEAR(b.y, a.x, 1e-9 * a.x);
    double worst = 0;
    for (const Vec3& wi : {direction_deg(30, 10), direction_deg(65, 150), direction_deg(80, -70)})
        for (double theta_o : {5.0, 35.0, 70.0})
            for (double phi_o : {0.0, 60.0, 150.0, 250.0}) {
                const Vec3 wo = direction_deg(theta_o, phi_o);
                const double f = base->eval(wi, wo, lambda);
                if (f < 1e-6) continue;
                worst = std::max(worst, std::abs(swapped->eval(wi, wo, lambda) / f - 1));
            }
    EXPECT_LT(worst, 1e-9);
    fmt::print("relabelling A + 90 deg, LU <-> LV: {:.2g} relative\n", worst);
}
