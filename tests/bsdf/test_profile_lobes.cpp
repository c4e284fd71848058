// The 1-D forms of GHS, SSA and Kirchhoff (bsdf/profile_lobes.hpp) against computations written here: the lobe S_g
// by adaptive quadrature of its ACV integral, the first orders against the closed 1-D KC and Gaussian PSDs, energy
// by Simpson's rule over theta_o, and the small-roughness limit against first-order perturbation theory (Rice).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <limits>
#include <vector>

#include "surfscatter/bsdf/profile_lobes.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/height_map_fft.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/relevant_roughness.hpp"
#include "surfscatter/surface/sharp_cut.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace sb = surfscatter::bsdf;
namespace sm = surfscatter::material;
namespace ss = surfscatter::surface;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180;

// S_g(zeta) = (1/pi) int_0^inf e^{-g} (e^{g rho} - 1) cos(zeta x) dx by adaptive Gauss-Kronrod on pieces: a geometric
// run toward x = 0 (the cusp of 1 - rho), then pieces at most half a period long out to 80 L.
double reference_lobe(const ss::RadialStatistics& stats, double g, double zeta) {
    const double length = stats.correlation_length();
    const auto f = [&](double x) {
        const double rho = stats.acv_normalized(x);
        return (std::exp(-g * (1 - rho)) - std::exp(-g)) * std::cos(zeta * x);
    };
    double sum = 0, a = 0;
    for (double b = length * 1e-14; b < length; b *= 4) {
        sum += surfscatter::math::integrate_adaptive(f, a, b, 1e-12, 1e-18);
        a = b;
    }
    const double step = std::min(length, zeta > 0 ? kPi / zeta : length);
    for (; a < 80 * length; a += step) sum += surfscatter::math::integrate_adaptive(f, a, a + step, 1e-12, 1e-18);
    return sum / kPi;
}

// The unit-mass 1-D PSDs of the cuts, closed forms (THEORY 2.1): KC (gamma-1) L Gamma(gamma/2) / (2 sqrt(pi)
// Gamma((gamma+1)/2)) (1 + L^2 zeta^2)^(-gamma/2); Gaussian l / (2 sqrt(pi)) exp(-l^2 zeta^2 / 4).
double kc_profile_psd_unit(double length, double gamma, double zeta) {
    return (gamma - 1) * length * std::tgamma(gamma / 2) / (2 * std::sqrt(kPi) * std::tgamma((gamma + 1) / 2)) *
           std::pow(1 + length * length * zeta * zeta, -gamma / 2);
}
double gaussian_profile_psd_unit(double length, double zeta) {
    return length / (2 * std::sqrt(kPi)) * std::exp(-length * length * zeta * zeta / 4);
}

std::vector<double> theta_grid(double step_deg) {
    std::vector<double> grid;
    for (double t = -90; t <= 90 + 1e-9; t += step_deg) grid.push_back(t * kDeg);
    return grid;
}

// Simpson's rule over an odd number of equally spaced samples.
double simpson(const std::vector<double>& y, double step) {
    double sum = y.front() + y.back();
    for (std::size_t j = 1; j + 1 < y.size(); ++j) sum += (j % 2 ? 4 : 2) * y[j];
    return sum * step / 3;
}

}  // namespace

// The lobe from its definition: within 1e-9 of S_g(0) (measured 4e-12), KC gamma 1.5 and 3 and a Gaussian ACV,
// optical roughness 0.05 to 20, |zeta| up to 2 k at 550 nm.
TEST(ProfileLobes, LobeMatchesAdaptiveQuadrature) {
    const double k = ss::wavenumber_per_um(550);
    const ss::KCorrelation kc3(0.1, 1.5, 3), kc15(0.1, 0.8, 1.5);
    const ss::GaussianAcv gaussian(0.1, 1.2);
    double worst = 0;
    for (const ss::RadialStatistics* stats : std::initializer_list<const ss::RadialStatistics*>{&kc3, &kc15, &gaussian}) {
        const sb::ProfileAcvTransform transform(*stats, 2 * k);
        for (const double g : {0.05, 1.0, 20.0, 300.0, 3000.0}) {
            const double peak = reference_lobe(*stats, g, 0);
            for (const double zeta : {0.0, 0.3, 2.0, 7.0, 15.0, 2 * k}) {
                const double error = std::abs(transform.lobe(g, zeta) - reference_lobe(*stats, g, zeta)) / peak;
                worst = std::max(worst, error);
                EXPECT_LT(error, 1e-9) << stats->cache_key() << " g " << g << " zeta " << zeta;
            }
        }
    }
    std::printf("[ measured ] worst |S_g - reference| / S_g(0): %.2e\n", worst);
}

// m = 1 is the 1-D PSD of the cut (within 1e-13 of the peak plus 1e-8 relative over the visible band; the far tail
// of gamma 4 at 2 k, 4e-7 of the peak, is 1.8e-9 off, the rule's round-off); gamma = 2 has rho = e^{-x/L}
// and the closed m = 2 order (2/L) / (pi ((2/L)^2 + zeta^2)).
TEST(ProfileLobes, FirstOrderIsTheKcProfilePsd) {
    const double k = ss::wavenumber_per_um(550);
    for (const double gamma : {1.5, 2.0, 3.0, 4.0}) {
        const ss::KCorrelation kc(0.05, 2.0, gamma);
        const sb::ProfileAcvTransform transform(kc, 2 * k);
        for (const double zeta : {0.0, 0.1, 1.0, 5.0, 2 * k}) {
            const double expected = kc_profile_psd_unit(2.0, gamma, zeta), peak = kc_profile_psd_unit(2.0, gamma, 0);
            EXPECT_NEAR(transform.order(1, zeta), expected, 1e-13 * peak + 1e-8 * expected) << gamma << " " << zeta;
            EXPECT_NEAR(ss::profile_psd(kc, zeta) / (0.05 * 0.05), expected, 1e-8 * expected);
            if (gamma == 2.0) {
                const double a = 2 / 2.0, order2 = a / (kPi * (a * a + zeta * zeta));
                EXPECT_NEAR(transform.order(2, zeta), order2, 1e-9 * order2) << zeta;
            }
        }
    }
    const ss::GaussianAcv gaussian(0.05, 1.0);
    const sb::ProfileAcvTransform transform(gaussian, 2 * k);
    for (const double zeta : {0.0, 1.0, 3.0, 6.0}) {
        const double expected = gaussian_profile_psd_unit(1.0, zeta);
        EXPECT_NEAR(transform.order(1, zeta), expected, 1e-9 * std::max(expected, 1e-3)) << zeta;
    }
}

// With the albedo normalisation the coherent fraction plus the lobe's integral over theta_o (Simpson on the CLI's
// 0.1 deg grid, written here) is R(theta_i) of the polarisation: within 1e-8 for the perfect conductor and gold, s and
// p, theta_i 0 / 60 / 80, GHS and the SSA energy form (measured 6e-13). Kirchhoff and the strict SSA are not energy-bounded: their albedos
// are printed.
TEST(ProfileLobes, GhsConservesEnergy) {
    const ss::KCorrelation kc(0.08, 1.5, 3);
    const auto grid = theta_grid(0.1);
    const auto gold = sm::Conductor::from_name("Au");
    double worst = 0;
    for (const bool metal : {false, true}) {
        const auto conductor = metal ? gold : sm::Conductor::perfect();
        for (const auto pol : {sb::ProfilePolarisation::s, sb::ProfilePolarisation::p})
            for (const double theta_i : {0.0, 60.0, 80.0})
                for (const auto model : {sb::ProfileModel::ghs, sb::ProfileModel::ghs_ssa, sb::ProfileModel::kirchhoff}) {
                    sb::ProfileModelOptions options;
                    options.model = model;
                    const auto lobe = sb::profile_lobe(kc, conductor, 550, theta_i * kDeg, pol, options, grid);
                    const double albedo = lobe.coherent + simpson(lobe.intensity_per_rad, 0.1 * kDeg);
                    const auto r = conductor.reflectance_sp(std::cos(theta_i * kDeg), 550);
                    const double expected = pol == sb::ProfilePolarisation::s ? r.rs : r.rp;
                    if (model == sb::ProfileModel::kirchhoff) {
                        std::printf("[ measured ] kirchhoff albedo %s %s theta_i %g: %.5f (R %.5f)\n",
                                    conductor.name().c_str(), pol == sb::ProfilePolarisation::s ? "s" : "p", theta_i,
                                    albedo, expected);
                        continue;
                    }
                    worst = std::max(worst, std::abs(albedo - expected));
                    EXPECT_NEAR(albedo, expected, 1e-8) << sb::to_string(model) << " theta_i " << theta_i;
                }
    }
    std::printf("[ measured ] worst |albedo - R| (ghs, ghs_ssa energy): %.2e\n", worst);
}

// First-order perturbation theory (Rice) for s on a perfect conductor, per radian: 4 k^3 cos i cos^2 o P1(zeta). The
// strict SSA is the GHS's first-order term k^3 cos o (cos i + cos o)^2 P1: equal at the specular direction, their
// ratio (cos i + cos o)^2 / (4 cos i cos o) elsewhere (THEORY 1.4), to 1e-9. GHS without renormalisation tends to it
// as O(g) (g = 2e-3 here: within 2e-3), Kirchhoff to k^3 (1 + cos(i + o))^2 P1 / cos i.
TEST(ProfileLobes, SmallRoughnessMatchesPerturbationTheory) {
    const double sigma = 0.002, length = 1.0, gamma = 3, lambda = 550, k = ss::wavenumber_per_um(lambda);
    const ss::KCorrelation kc(sigma, length, gamma);
    const double theta_i = 20 * kDeg, ci = std::cos(theta_i);
    std::vector<double> grid;
    for (double t = -80; t <= 80; t += 10) grid.push_back(t * kDeg);
    grid.push_back(theta_i);
    const auto lobe_of = [&](sb::ProfileModel model, sb::SsaForm form, bool renormalization) {
        sb::ProfileModelOptions options;
        options.model = model;
        options.ssa_form = form;
        options.renormalization = renormalization;
        return sb::profile_lobe(kc, sm::Conductor::perfect(), lambda, theta_i, sb::ProfilePolarisation::s, options,
                                grid);
    };
    const auto strict = lobe_of(sb::ProfileModel::ghs_ssa, sb::SsaForm::strict, true);
    const auto ghs = lobe_of(sb::ProfileModel::ghs, sb::SsaForm::energy, false);
    const auto kirchhoff = lobe_of(sb::ProfileModel::kirchhoff, sb::SsaForm::energy, true);
    for (std::size_t j = 0; j < grid.size(); ++j) {
        const double co = std::cos(grid[j]), zeta = k * (std::sin(grid[j]) - std::sin(theta_i));
        const double p1 = sigma * sigma * kc_profile_psd_unit(length, gamma, zeta);
        const double rice = 4 * k * k * k * ci * co * co * p1;
        const double ratio = (ci + co) * (ci + co) / (4 * ci * co);
        EXPECT_NEAR(strict.intensity_per_rad[j], rice * ratio, 1e-9 * rice * ratio) << grid[j] / kDeg;
        EXPECT_NEAR(ghs.intensity_per_rad[j], rice * ratio, 2e-3 * rice * ratio) << grid[j] / kDeg;
        const double obliquity = 1 + std::cos(theta_i + grid[j]);
        const double kirchhoff_limit = k * k * k * obliquity * obliquity * p1 / ci;
        EXPECT_NEAR(kirchhoff.intensity_per_rad[j], kirchhoff_limit, 2e-3 * kirchhoff_limit) << grid[j] / kDeg;
    }
    const double specular_rice = 4 * k * k * k * ci * ci * ci * sigma * sigma * kc_profile_psd_unit(length, gamma, 0);
    EXPECT_NEAR(strict.intensity_per_rad.back(), specular_rice, 1e-9 * specular_rice);
    EXPECT_NEAR(kirchhoff.intensity_per_rad.back(), specular_rice, 2e-3 * specular_rice);
    EXPECT_NEAR(strict.coherent, std::exp(-std::pow(2 * k * sigma * ci, 2)), 1e-12);
}

// The 1-D relevant roughness is the profile PSD's mass over the visible interval (closed KC gamma = 2 form:
// P1-hat = L / (pi (1 + L^2 zeta^2)), mass (atan(L b) - atan(L a)) / pi).
TEST(ProfileLobes, RelevantRoughnessIsTheVisibleMass) {
    const double length = 0.3, k = ss::wavenumber_per_um(633);
    const ss::KCorrelation kc(0.1, length, 2);
    for (const double theta : {0.0, 40.0, 85.0}) {
        const double s = std::sin(theta * kDeg);
        const double mass = (std::atan(length * k * (1 - s)) + std::atan(length * k * (1 + s))) / kPi;
        EXPECT_NEAR(sb::profile_relevant_roughness(kc, theta * kDeg, 633), 0.1 * std::sqrt(mass), 1e-9) << theta;
    }
}

// The Rayleigh-Rice factor of the polarisation equals |r|^2 at the specular direction (gold, s and p); every model is
// finite at grazing angles; bad inputs are errors naming the value.
TEST(ProfileLobes, FresnelModesGrazingAndErrors) {
    const ss::GaussianAcv gaussian(0.05, 1.0);
    const auto gold = sm::Conductor::from_name("Au");
    const double theta_i = 50 * kDeg;
    for (const auto pol : {sb::ProfilePolarisation::s, sb::ProfilePolarisation::p}) {
        sb::ProfileModelOptions incident, rr, half;
        rr.fresnel = sb::FresnelMode::rr;
        half.fresnel = sb::FresnelMode::half;
        const std::vector<double> specular{theta_i};
        const double a = sb::profile_lobe(gaussian, gold, 600, theta_i, pol, incident, specular).intensity_per_rad[0];
        EXPECT_NEAR(sb::profile_lobe(gaussian, gold, 600, theta_i, pol, rr, specular).intensity_per_rad[0], a, 1e-12 * a);
        EXPECT_NEAR(sb::profile_lobe(gaussian, gold, 600, theta_i, pol, half, specular).intensity_per_rad[0], a, 1e-12 * a);
    }
    const std::vector<double> edges{-90 * kDeg, -89.9 * kDeg, 89.9 * kDeg, 90 * kDeg};
    for (const auto model : {sb::ProfileModel::ghs, sb::ProfileModel::ghs_ssa, sb::ProfileModel::kirchhoff})
        for (const auto fresnel : {sb::FresnelMode::incident, sb::FresnelMode::half, sb::FresnelMode::rr}) {
            sb::ProfileModelOptions options;
            options.model = model;
            options.fresnel = model == sb::ProfileModel::kirchhoff ? sb::FresnelMode::incident : fresnel;
            for (const auto& conductor : {sm::Conductor::perfect(), gold}) {
                const auto lobe = sb::profile_lobe(gaussian, conductor, 600, 89.9 * kDeg, sb::ProfilePolarisation::p,
                                                   options, edges);
                for (const double v : lobe.intensity_per_rad) EXPECT_TRUE(std::isfinite(v));
                EXPECT_TRUE(std::isfinite(lobe.coherent));
            }
        }
    const std::vector<double> one{0.0};
    EXPECT_THROW(sb::profile_lobe(gaussian, gold, 600, 90 * kDeg, sb::ProfilePolarisation::s, {}, one),
                 surfscatter::Error);
    EXPECT_THROW(sb::profile_lobe(gaussian, gold, -1, 0, sb::ProfilePolarisation::s, {}, one), surfscatter::Error);
    EXPECT_THROW(sb::profile_lobe(gaussian, gold, 0.01, 0, sb::ProfilePolarisation::s, {}, one), surfscatter::Error);
    EXPECT_THROW(sb::profile_lobe(ss::GaussianAcv(0.05, 1e5), sm::Conductor::perfect(), 100, 0,
                                  sb::ProfilePolarisation::s, {}, one),
                 surfscatter::Error);
    EXPECT_THROW(sb::profile_lobe(gaussian, gold, 600, 0, sb::ProfilePolarisation::s, {}, {2.0}), surfscatter::Error);
    // A lobe spread far beyond the visible band (gamma 1.05, sigma 100 um): S_g underflows there, K cannot exist.
    EXPECT_THROW(sb::profile_lobe(ss::KCorrelation(100, 1, 1.05), sm::Conductor::perfect(), 550, 0,
                                  sb::ProfilePolarisation::s, {}, one),
                 surfscatter::Error);
    EXPECT_THROW(sb::parse_profile_model("ggx_stats"), surfscatter::Error);
}

// The 1-D GGX form against an independent computation written here: the slope density along x by quadrature of
// GGX's 2-D slope density over the slope along y (not the closed marginal), Smith's Lambda by quadrature of
// (1/mu) int_mu^inf (q - mu) P2(q) dq with mu = cot theta, and the geometric-optics lobe assembled from them; and the
// lobe's mass with F = 1 and no shadowing is the share of facets the visible directions reach.
TEST(ProfileLobes, GgxFormMatchesQuadratureOfTheSlopeDensity) {
    const ss::KCorrelation surface(0.15, 4.0, 4.0);
    const double alpha2 = surface.mean_square_slope(0.0, std::numeric_limits<double>::infinity());
    const double alpha = std::sqrt(alpha2);
    const auto p22 = [&](double p, double q) {
        const double r = 1 + (p * p + q * q) / alpha2;
        return 1 / (kPi * alpha2 * r * r);
    };
    const auto simpson = [](auto f, double a, double b, int n) {  // composite Simpson, n even
        const double h = (b - a) / n;
        double sum = f(a) + f(b);
        for (int j = 1; j < n; ++j) sum += (j % 2 ? 4 : 2) * f(a + j * h);
        return sum * h / 3;
    };
    // q = c tan t, c = sqrt(alpha^2 + p^2) (the density's own width at this p), maps the real line onto
    // (-pi/2, pi/2).
    const auto p2 = [&](double p) {
        const double c = std::sqrt(alpha2 + p * p);
        return simpson([&](double t) { return t * t >= kPi * kPi / 4 ? 0.0 : p22(p, c * std::tan(t)) * c /
                                                                                   (std::cos(t) * std::cos(t)); },
                       -kPi / 2, kPi / 2, 400);
    };
    const auto smith = [&](double theta) {
        if (theta == 0) return 0.0;
        const double mu = 1 / std::tan(std::abs(theta));
        const double t0 = std::atan(mu / alpha);  // q = alpha tan t from mu to infinity
        return simpson([&](double t) {
                   if (t >= kPi / 2) return 0.0;
                   const double q = alpha * std::tan(t);
                   return (q - mu) * p2(q) * alpha / (std::cos(t) * std::cos(t));
               }, t0, kPi / 2 - 1e-9, 2000) / mu;
    };
    const auto silver = sm::Conductor::from_name("Ag");
    for (const double theta_i_deg : {0.0, 30.0, 60.0})
        for (const auto polarisation : {sb::ProfilePolarisation::s, sb::ProfilePolarisation::p}) {
            const double ti = theta_i_deg * kPi / 180;
            const std::vector<double> theta_o{-1.2, -0.5, 0.0, 0.3, ti, 0.9, 1.4};
            const auto lobe = sb::ggx_profile_lobe(surface, silver, 550, ti, polarisation, theta_o);
            EXPECT_EQ(lobe.coherent, 0.0);
            const double lambda_i = smith(ti);
            for (std::size_t j = 0; j < theta_o.size(); ++j) {
                const double to = theta_o[j], b = (to - ti) / 2, td = (ti + to) / 2;
                const auto r = silver.reflectance_sp(std::cos(td), 550);
                const double f = polarisation == sb::ProfilePolarisation::s ? r.rs : r.rp;
                const double expected = f / (1 + lambda_i + smith(to)) * p2(std::tan(b)) * std::cos(td) /
                                        (2 * std::pow(std::cos(b), 3) * std::cos(ti));
                EXPECT_NEAR(lobe.intensity_per_rad[j], expected, 1e-6 * expected)
                    << theta_i_deg << " deg, theta_o " << to;
            }
        }
    EXPECT_THROW(sb::ggx_profile_lobe(ss::KCorrelation(0.15, 4.0, 3.0), silver, 550, 0.0, sb::ProfilePolarisation::s,
                                      {0.0}),
                 surfscatter::Error);
}

namespace {

// The profile PSD of a sharp cut's high-pass part, written here: int over zeta_y of KC's unit 2-D PSD
// (gamma - 1) L^2 / (2 pi) (1 + L^2 zeta^2)^(-(gamma + 1) / 2) where sqrt(zeta_x^2 + zeta_y^2) > zeta_c, normalised
// to unit mass (over 1 - F_c, F_c = 1 - (1 + L^2 zeta_c^2)^(-(gamma - 1) / 2)).
double kc_high_pass_profile_psd_unit(double length, double gamma, double zeta_c, double zeta_x) {
    const double y0 = std::abs(zeta_x) < zeta_c ? std::sqrt(zeta_c * zeta_c - zeta_x * zeta_x) : 0.0;
    const double c = std::max(std::abs(zeta_x), 1 / length);
    const auto f = [&](double u) {
        if (u >= 1) return 0.0;
        const double zy = y0 + c * u / (1 - u), z2 = zeta_x * zeta_x + zy * zy;
        return (gamma - 1) * length * length / (2 * kPi) * std::pow(1 + length * length * z2, -(gamma + 1) / 2) * c /
               ((1 - u) * (1 - u));
    };
    const double fraction = std::pow(1 + length * length * zeta_c * zeta_c, -(gamma - 1) / 2);
    return 2 * surfscatter::math::integrate_adaptive(f, 0.0, 1.0, 1e-12) / fraction;
}

}  // namespace

// The high-pass part of a sharp cut (two_scale's micro statistics) from the PSD side, independent of its ACV: the
// Poisson series e^{-g} sum_m g^m / m! P1-hat^{*m}(zeta) summed in closed form on a uniform zeta grid (the circular
// convolutions by FFT: e^{g F} - 1 of the grid's transform F), P1-hat_HP by quadrature of KC's 2-D PSD outside the
// disc. The 1-D lobe reads its first order from the PSD and the rest from the ringing ACV with a tapered end; read
// whole from the ACV cut off where it first falls below 1e-17 (where the ringing first turns negative), it was off by
// up to 28x (g 0.3), 14x (g 1), 1.7x (g 3). KC sigma 0.02 um, L 2 um, gamma 3 (the supplemental's smooth surface),
// zeta_c = k(550 nm) / 100; g 0.3 to 10; zeta from 0 to 2 k: within 2e-4 relative + 1e-7 of the peak (measured 0.44
// of that bound).
TEST(ProfileLobes, TwoScaleMicroLobeMatchesThePoissonSeriesOfItsPsd) {
    const double length = 2.0, gamma = 3.0, k = ss::wavenumber_per_um(550), zeta_c = k / 100;
    const auto base = std::make_shared<ss::KCorrelation>(0.02, length, gamma);
    const ss::SharpCutStatistics micro(base, zeta_c, ss::CutPart::high_pass);
    const sb::ProfileAcvTransform transform(micro, 2 * k);
    // The grid: zeta_j = j d, |j| < n / 2, d = 0.004 rad/um (28 points across zeta_c), |zeta| < 256 rad/um.
    const std::size_t n = std::size_t(1) << 17;
    const double d = 512.0 / double(n);
    std::vector<double> mass(n);
    for (std::size_t j = 0; j <= n / 2; ++j) {
        const double p = kc_high_pass_profile_psd_unit(length, gamma, zeta_c, double(j) * d) * d;
        mass[j] = p;
        if (j > 0 && j < n / 2) mass[n - j] = p;
    }
    // The rectangle rule misses 5e-5 of the unit mass at the square-root edge of P1-hat_HP at zeta_c: rescaled to it
    // (the g-fold mass error would otherwise offset the lobe by ~g 5e-5 everywhere).
    double total = 0;
    for (const double m : mass) total += m;
    for (double& m : mass) m /= total;
    const auto spectrum = surfscatter::heightmap::forward_fft_2d(mass, n, 1);
    double worst = 0;
    for (const double g : {0.3, 1.0, 3.0, 10.0}) {
        auto series = spectrum;
        for (auto& f : series) f = std::exp(-g) * (std::exp(g * f) - 1.0);
        const std::vector<double> lobe = surfscatter::heightmap::inverse_fft_2d(series, n, 1);  // x n d
        const double peak = lobe[0] / (double(n) * d);
        for (std::size_t j = 0; double(j) * d <= 2 * k; j += double(j) * d < 3 * zeta_c ? 3 : 37) {
            const double expected = lobe[j] / (double(n) * d), got = transform.lobe(g, double(j) * d);
            const double error = std::abs(got - expected) / (2e-4 * expected + 1e-7 * peak);
            worst = std::max(worst, error);
            EXPECT_LE(error, 1.0) << "g " << g << ", zeta " << double(j) * d << ": " << got << " against " << expected;
        }
    }
    std::printf("[ measured ] two_scale micro lobe against the Poisson series: worst %.3g of the bound\n", worst);
}

// two_scale's limits: no roughness above the split (a Gaussian ACV cut at 100 k: nothing above it) is the 1-D GGX of
// the slopes (ggx_profile_lobe, tested against quadrature above) to 1e-9; no roughness below it (cut at k / 1e4:
// 5e-6 of the variance below) is the GHS of the whole surface away from the macro facets' spike at specular (at most
// 1e-4 apart, measured below), with no coherent part. Perfect conductor and Au, s and p, theta_i 0, 30, 60.
TEST(ProfileLobes, TwoScaleLimitsAreTheGgxOfTheSlopesAndTheGhs) {
    const auto gold = sm::Conductor::from_name("Au");
    const ss::GaussianAcv gaussian(0.1, 2.0);
    const ss::KCorrelation kc(0.02, 2.0, 3.0);
    double worst = 0;
    for (const sm::Conductor* conductor : {&gold, static_cast<const sm::Conductor*>(nullptr)}) {
        const sm::Conductor metal = conductor ? *conductor : sm::Conductor::perfect();
        for (const double theta_i_deg : {0.0, 30.0, 60.0})
            for (const auto polarisation : {sb::ProfilePolarisation::s, sb::ProfilePolarisation::p}) {
                const double ti = theta_i_deg * kDeg;
                std::vector<double> theta_o;
                for (double t = -85; t <= 85; t += 5)
                    if (std::abs(t - theta_i_deg) >= 1) theta_o.push_back(t * kDeg);
                const auto macro_only = sb::two_scale_profile_lobe(gaussian, metal, 550, ti, polarisation, theta_o, 0.01);
                const auto ggx = sb::ggx_profile_lobe(gaussian, metal, 550, ti, polarisation, theta_o);
                EXPECT_EQ(macro_only.coherent, 0.0);
                for (std::size_t j = 0; j < theta_o.size(); ++j)
                    EXPECT_NEAR(macro_only.intensity_per_rad[j], ggx.intensity_per_rad[j],
                                1e-9 * ggx.intensity_per_rad[j]);
                const auto micro_only = sb::two_scale_profile_lobe(kc, metal, 550, ti, polarisation, theta_o, 1e4);
                const auto ghs = sb::profile_lobe(kc, metal, 550, ti, polarisation, {}, theta_o);
                EXPECT_EQ(micro_only.coherent, 0.0);
                for (std::size_t j = 0; j < theta_o.size(); ++j) {
                    const double error = std::abs(micro_only.intensity_per_rad[j] / ghs.intensity_per_rad[j] - 1);
                    worst = std::max(worst, error);
                    EXPECT_LE(error, 1e-4) << theta_i_deg << " deg, theta_o " << theta_o[j] / kDeg;
                }
            }
    }
    std::printf("[ measured ] two_scale without macro roughness against the GHS: worst %.3g\n", worst);
    EXPECT_THROW(sb::two_scale_profile_lobe(kc, gold, 550, 0.0, sb::ProfilePolarisation::s, {0.0}, 0.0),
                 surfscatter::Error);
}
