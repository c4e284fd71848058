// The Kirchhoff BRDF of a height map against references written here: a direct per-direction sum, the flat mirror
// (Fresnel), the geometric-optics limit from the map's own slopes, the project's GHS near normal incidence, energy,
// and a grating's orders against the Jacobi-Anger (Bessel) closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <complex>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include "surfscatter/bsdf/factory.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/core/progress.hpp"
#include "surfscatter/material/conductor.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/kirchhoff_map.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/radial_statistics.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace {

namespace sr = surfscatter::reference;
namespace ss = surfscatter::surface;
namespace hm = surfscatter::heightmap;
using surfscatter::kDegree;
using surfscatter::kPi;
using surfscatter::material::Conductor;

sr::KirchhoffOptions options(double lambda_nm, double theta_i_deg, double subarea_um, double phi_i_deg = 0) {
    sr::KirchhoffOptions o;
    o.lambda_nm = lambda_nm;
    o.theta_i_rad = theta_i_deg * kDegree;
    o.phi_i_rad = phi_i_deg * kDegree;
    o.subarea_um = subarea_um;
    return o;
}

double hann(std::size_t j, std::size_t n) {
    const double s = std::sin(kPi * (static_cast<double>(j) + 0.5) / static_cast<double>(n));
    return s * s;
}

// f_r per |I|^2 / A_W (the header's formula), for the direct sum and the grating's closed form.
double prefactor(double k, double theta_i, double phi_i, double ox, double oy, double fresnel) {
    const double ix = std::sin(theta_i) * std::cos(phi_i), iy = std::sin(theta_i) * std::sin(phi_i);
    const double cos_i = std::cos(theta_i), cos_o = std::sqrt(1 - ox * ox - oy * oy);
    const double q2 = k * k * ((ix + ox) * (ix + ox) + (iy + oy) * (iy + oy) + (cos_i + cos_o) * (cos_i + cos_o));
    const double qz = k * (cos_i + cos_o);
    return fresnel * q2 * q2 / (16 * kPi * kPi * qz * qz * cos_i * cos_o);
}

// The flux of a plane-wave component (a mirror, a grating order) of power weight(o_x, o_y) at lattice direction
// (ox, oy), spread by the window: the Hann window's DFT has 3 x 3 non-zero bins, energy weights (1, 4, 1) / 6 per
// axis, and the lattice sum of |W^|^2 times the cell is 4 pi^2 A_W / k^2 (Parseval).
double lobe_flux(double k, double theta_i, double phi_i, double ox, double oy, double step_x, double step_y,
                 const std::function<double(double, double)>& weight) {
    const double w[3] = {1.0 / 6, 4.0 / 6, 1.0 / 6};
    double sum = 0;
    for (int b = -1; b <= 1; ++b)
        for (int a = -1; a <= 1; ++a) {
            const double x = ox + a * step_x, y = oy + b * step_y;
            sum += w[a + 1] * w[b + 1] * prefactor(k, theta_i, phi_i, x, y, 1.0) * weight(x, y);
        }
    return sum * 4 * kPi * kPi / (k * k);
}

// Every direction's amplitude summed directly over the pixels (no FFT, no q_z bands): the tiles of an exactly
// divisible map, phases from each tile's corner.
TEST(KirchhoffMap, BandExpansionMatchesDirectSum) {
    // Two long waves (heights +-0.4 um over a sub-area, so several q_z bands) and fine roughness.
    const double dx = 0.025, lambda_um = 0.3;
    const hm::HeightMap rough = ss::synthesize_surface(ss::GaussianAcv(0.05, 0.2), {256, 128, dx}, 3);
    std::vector<double> h = rough.heights();
    for (std::size_t y = 0; y < 128; ++y)
        for (std::size_t x = 0; x < 256; ++x)
            h[y * 256 + x] += 0.25 * std::cos(2 * kPi * dx * static_cast<double>(x) / 3.2) +
                              0.15 * std::sin(2 * kPi * dx * static_cast<double>(y) / 1.6 + 0.3);
    const hm::HeightMap map(256, 128, dx, dx, h, "waves");
    const auto o = options(1e3 * lambda_um, 25, 3.2, 30);
    const auto result = sr::kirchhoff_brdf(map, Conductor::perfect(), o);
    ASSERT_EQ(result.subareas, 2u);
    EXPECT_GT(result.band_count, 1u);
    const double k = 2 * kPi / lambda_um;
    const std::size_t n = 128;
    double window_area = 0;
    for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) window_area += std::pow(hann(x, n) * hann(y, n), 2) * dx * dx;
    const double ix = std::sin(o.theta_i_rad) * std::cos(o.phi_i_rad);
    const double iy = std::sin(o.theta_i_rad) * std::sin(o.phi_i_rad);
    double worst = 0, peak = 0;
    for (std::size_t d = 0; d < result.brdf.size(); ++d) {
        const double ox = result.o_x[d], oy = result.o_y[d];
        const double qx = k * (ix + ox), qy = k * (iy + oy);
        const double qz = k * (std::cos(o.theta_i_rad) + std::sqrt(1 - ox * ox - oy * oy));
        double mean = 0;
        for (std::size_t tile = 0; tile < 2; ++tile) {
            std::complex<double> sum = 0;
            for (std::size_t y = 0; y < n; ++y)
                for (std::size_t x = 0; x < n; ++x) {
                    const double phase = qx * dx * static_cast<double>(x) + qy * dx * static_cast<double>(y) +
                                         qz * map(tile * n + x, y);
                    sum += hann(x, n) * hann(y, n) * dx * dx * std::polar(1.0, phase);
                }
            mean += std::norm(sum) / 2;
        }
        const double expected = prefactor(k, o.theta_i_rad, o.phi_i_rad, ox, oy, 1.0) * mean / window_area;
        worst = std::max(worst, std::abs(result.brdf[d] - expected));
        peak = std::max(peak, expected);
    }
    EXPECT_LT(worst / peak, 1e-10) << "worst " << worst << " peak " << peak;
}

// A flat map is a mirror: all of it coherent, its flux the window's lobe about the specular direction exactly, and
// that within 3 step^2 of the Fresnel reflectance at theta_i (the lobe's directions see other obliquities).
TEST(KirchhoffMap, FlatMapIsTheFresnelMirror) {
    const hm::HeightMap flat(256, 256, 0.1, 0.1, std::vector<double>(256 * 256, 0.0), "flat");
    const double k = 2 * kPi / 0.55, phi_i = 20 * kDegree;
    for (const char* metal : {"perfect", "Ag", "Au"})
        for (double theta : {0.0, 30.0, 60.0}) {
            const Conductor conductor = Conductor::from_name(metal);
            const auto r = sr::kirchhoff_brdf(flat, conductor, options(550, theta, 12.8, 20));
            const double theta_i = theta * kDegree;
            const double ix = std::sin(theta_i) * std::cos(phi_i), iy = std::sin(theta_i) * std::sin(phi_i);
            const double lobe = lobe_flux(k, theta_i, phi_i, -ix, -iy, r.step_x, r.step_y, [&](double x, double y) {
                const double cos_o = std::sqrt(1 - x * x - y * y);
                const double half = std::sqrt((ix + x) * (ix + x) + (iy + y) * (iy + y) +
                                              (std::cos(theta_i) + cos_o) * (std::cos(theta_i) + cos_o)) / 2;
                return conductor.reflectance(half, 550);
            });
            EXPECT_NEAR(r.albedo, lobe, 1e-9 * lobe) << metal << " theta_i " << theta;
            const double fresnel = conductor.reflectance(std::cos(theta_i), 550);
            EXPECT_NEAR(r.albedo, fresnel, 3 * r.step_x * r.step_y * fresnel) << metal << " theta_i " << theta;
            EXPECT_NEAR(r.coherent_albedo, r.albedo, 1e-12) << metal << " theta_i " << theta;
            EXPECT_EQ(r.albedo_standard_error, 0.0);
            EXPECT_TRUE(r.warnings.empty());
        }
}

// Large roughness: the BRDF integrated over coarse bins of o_xy equals the geometric optics of the map's own slopes
// (each pixel a mirror facet, weighted by the window squared as the Kirchhoff sum weights it).
TEST(KirchhoffMap, GeometricLimitIsTheMapsSlopeDistribution) {
    const ss::GaussianAcv statistics(0.5, 4.0);  // g = (2 k sigma)^2 ~ 160, rms slope per axis 0.18
    const hm::HeightMap map = ss::synthesize_surface(statistics, {1024, 1024, 0.1}, 11);
    const double lambda = 500, theta_i = 20 * kDegree;
    const Conductor gold = Conductor::from_name("Au");
    const auto r = sr::kirchhoff_brdf(map, gold, options(lambda, 20, 25.6));
    ASSERT_EQ(r.subareas, 16u);
    // Bins of 10 x 10 lattice cells (0.2 in direction cosines; ~1,700 speckles each, so ~2.5 % noise), a direction
    // counted in the cell it falls in.
    const auto key = [&](double ox, double oy) {
        const long mx = std::lround((ox + std::sin(theta_i)) / r.step_x), my = std::lround(oy / r.step_y);
        return std::pair{static_cast<int>(std::floor(static_cast<double>(mx) / 10)),
                         static_cast<int>(std::floor(static_cast<double>(my) / 10))};
    };
    std::map<std::pair<int, int>, double> kirchhoff, geometric;
    for (std::size_t d = 0; d < r.brdf.size(); ++d)
        kirchhoff[key(r.o_x[d], r.o_y[d])] += r.brdf[d] * r.step_x * r.step_y;
    const std::size_t n = 256;
    double window_square = 0;
    for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) window_square += std::pow(hann(x, n) * hann(y, n), 2);
    const surfscatter::Vec3 wi{std::sin(theta_i), 0, std::cos(theta_i)};
    const double max_sin = std::sin(85 * kDegree);
    for (std::size_t ty = 0; ty < 4; ++ty)
        for (std::size_t tx = 0; tx < 4; ++tx)
            for (std::size_t y = 0; y < n; ++y)
                for (std::size_t x = 0; x < n; ++x) {
                    const std::size_t px = tx * n + x, py = ty * n + y;
                    const std::size_t xm = px == 0 ? 0 : px - 1, xp = px + 1 == 1024 ? px : px + 1;
                    const std::size_t ym = py == 0 ? 0 : py - 1, yp = py + 1 == 1024 ? py : py + 1;
                    const double sx = (map(xp, py) - map(xm, py)) / (0.1 * static_cast<double>(xp - xm));
                    const double sy = (map(px, yp) - map(px, ym)) / (0.1 * static_cast<double>(yp - ym));
                    const double norm = std::sqrt(1 + sx * sx + sy * sy);
                    const surfscatter::Vec3 m{-sx / norm, -sy / norm, 1 / norm};
                    const double cos_d = dot(wi, m);
                    if (cos_d <= 0) continue;
                    const surfscatter::Vec3 wo = 2 * cos_d * m - wi;
                    if (wo.z <= 0 || wo.x * wo.x + wo.y * wo.y > max_sin * max_sin) continue;
                    const double weight = std::pow(hann(x, n) * hann(y, n), 2) / window_square / 16;
                    geometric[key(wo.x, wo.y)] +=
                        weight * gold.reflectance(cos_d, lambda) * cos_d / (m.z * std::cos(theta_i));
                }
    double total_geometric = 0, total_kirchhoff = 0, worst = 0;
    int compared = 0;
    for (const auto& [cell, flux] : geometric) total_geometric += flux;
    for (const auto& [cell, flux] : kirchhoff) total_kirchhoff += flux;
    for (const auto& [cell, flux] : geometric) {
        if (flux < 0.01 * total_geometric) continue;
        worst = std::max(worst, std::abs(kirchhoff[cell] / flux - 1));
        ++compared;
    }
    EXPECT_GT(compared, 8);
    EXPECT_LT(worst, 0.08) << "bins compared " << compared;
    EXPECT_NEAR(total_kirchhoff, total_geometric, 0.01 * total_geometric);
}

// Near normal incidence with small slopes GHS and Kirchhoff are the same scalar diffraction integral: the map's
// Kirchhoff BRDF against the GHS BRDF of the KC it was drawn from, averaged over rings about the specular direction
// (beyond the window's lobe), for small and large g; and a perfect conductor's albedo close to 1.
TEST(KirchhoffMap, AgreesWithGhsNearNormalIncidence) {
    const double lambda = 500, length = 2.0, gamma = 4.0, theta_i = 5;
    for (double sigma : {0.01, 0.15}) {  // g = (2 k sigma cos)^2 = 0.06 and 14
        const ss::KCorrelation kc(sigma, length, gamma);
        const hm::HeightMap map = ss::synthesize_surface(kc, {1024, 1024, 0.25}, 5);
        const auto r = sr::kirchhoff_brdf(map, Conductor::perfect(), options(lambda, theta_i, 64));
        ASSERT_EQ(r.subareas, 16u);
        surfscatter::bsdf::ModelOptions model;  // GHS with the PSD measured on this map
        model.surface.psd = surfscatter::bsdf::PsdKind::measured;
        model.surface.measured_spectrum = surfscatter::bsdf::MeasuredSpectrum::ring;  // the tolerances are the ring route's
        model.surface.measured_psd = std::make_shared<const ss::MapStatistics>(map, hm::Form::none);
        const auto ghs = surfscatter::bsdf::make_bsdf(model);
        const surfscatter::Vec3 wi{std::sin(theta_i * kDegree), 0, std::cos(theta_i * kDegree)};
        const double sx = -wi.x;
        std::map<int, std::pair<double, double>> rings;  // ring (in lattice steps) -> (Kirchhoff, GHS) sums
        for (std::size_t d = 0; d < r.brdf.size(); ++d) {
            const double ex = (r.o_x[d] - sx) / r.step_x, ey = r.o_y[d] / r.step_y;
            const int ring = static_cast<int>(std::sqrt(ex * ex + ey * ey) / 2);
            if (ring < 2) continue;  // the window's lobe about the specular peak
            const surfscatter::Vec3 wo{r.o_x[d], r.o_y[d], std::sqrt(1 - r.o_x[d] * r.o_x[d] - r.o_y[d] * r.o_y[d])};
            rings[ring].first += r.brdf[d];
            // The two theories' obliquity factors differ away from the specular direction (THEORY.md 1.5):
            // Kirchhoff / GHS = cos^2(theta_d) / (cos i cos o cos^2(theta_h)).
            const surfscatter::Vec3 sum = wi + wo;
            const double cos_d2 = dot(sum, sum) / 4, cos_h2 = sum.z * sum.z / dot(sum, sum);
            rings[ring].second += ghs->eval(wi, wo, lambda) * cos_d2 / (wi.z * wo.z * cos_h2);
        }
        const double peak = rings.begin()->second.second;
        double worst = 0;
        int compared = 0;
        for (const auto& [ring, sums] : rings) {
            if (sums.second < 0.01 * peak || ring > 40) continue;
            worst = std::max(worst, std::abs(sums.first / sums.second - 1));
            ++compared;
        }
        EXPECT_GT(compared, 5) << "sigma " << sigma;
        EXPECT_LT(worst, 0.1) << "sigma " << sigma << ", rings compared " << compared;
        EXPECT_NEAR(r.albedo, 1.0, 1e-3) << "sigma " << sigma;  // 1 + 2e-5 and 1 + 9e-5
        EXPECT_LT(r.albedo_standard_error, 0.01);
    }
}

// h = a cos(2 pi x / period): orders at o_x = -sin(theta_i) + m lambda / period with efficiency
// F * prefactor * J_m(q_z a)^2 (Jacobi-Anger), nothing between them.
TEST(KirchhoffMap, GratingOrdersFollowTheGratingEquation) {
    const double a = 0.1, period = 2.0, dx = 0.05, lambda = 500, theta_i = 10 * kDegree;
    const std::size_t nx = 640, ny = 320;
    std::vector<double> h(nx * ny);
    for (std::size_t y = 0; y < ny; ++y)
        for (std::size_t x = 0; x < nx; ++x)
            h[y * nx + x] = a * std::cos(2 * kPi * dx * static_cast<double>(x) / period);
    const hm::HeightMap grating(nx, ny, dx, dx, h, "grating");
    const auto r = sr::kirchhoff_brdf(grating, Conductor::perfect(), options(lambda, 10, 16));
    ASSERT_EQ(r.subareas, 2u);
    const double k = 2 * kPi / 0.5;
    std::map<int, double> order_flux;
    double stray = 0, total = 0;
    for (std::size_t d = 0; d < r.brdf.size(); ++d) {
        const double flux = r.brdf[d] * r.step_x * r.step_y;
        total += flux;
        // The order number for which the grating equation holds at this direction.
        const double m = (r.o_x[d] + std::sin(theta_i)) * period / 0.5;
        const long nearest = std::lround(m);
        const bool in_lobe = std::abs(m - static_cast<double>(nearest)) * 0.5 / period <= 1.01 * r.step_x &&
                             std::abs(r.o_y[d]) <= 1.01 * r.step_y;
        if (in_lobe) order_flux[static_cast<int>(nearest)] += flux;
        else stray += flux;
    }
    EXPECT_LT(stray, 1e-9 * total);
    int orders = 0;
    for (const auto& [m, flux] : order_flux) {
        const double ox = -std::sin(theta_i) + m * 0.5 / period;
        const double expected = lobe_flux(k, theta_i, 0, ox, 0, r.step_x, r.step_y, [&](double x, double y) {
            const double qz = k * (std::cos(theta_i) + std::sqrt(1 - x * x - y * y));
            return std::pow(std::cyl_bessel_j(std::abs(m), qz * a), 2);
        });
        EXPECT_NEAR(flux, expected, 1e-8 * expected) << "order " << m;
        ++orders;
    }
    EXPECT_EQ(orders, 8);  // m = -3 .. 4 propagate within 85 deg
}

TEST(KirchhoffMap, RefusesUntrustworthyInput) {
    const ss::GaussianAcv rough(1.0, 1.0);  // slopes ~1.4 on 0.2 um pixels: phase steps above pi at 400 nm
    const hm::HeightMap map = ss::synthesize_surface(rough, {128, 128, 0.2}, 1);
    EXPECT_THROW(sr::kirchhoff_brdf(map, Conductor::perfect(), options(400, 0, 12.8)), surfscatter::Error);
    EXPECT_THROW(sr::kirchhoff_brdf(map, Conductor::perfect(), options(400, 0, 2.0)), surfscatter::Error);   // 10 px
    EXPECT_THROW(sr::kirchhoff_brdf(map, Conductor::perfect(), options(400, 0, 25.6)), surfscatter::Error);  // 1 tile
    EXPECT_THROW(sr::kirchhoff_brdf(map, Conductor::perfect(), options(400, 90, 12.8)), surfscatter::Error);
}

bool has_warning(const sr::KirchhoffResult& r, const std::string& text) {
    return std::any_of(r.warnings.begin(), r.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

// Sub-areas far smaller than the correlation length leave the diffuse part inside the window's lobe; sub-areas with
// an invalid point are skipped; both said.
TEST(KirchhoffMap, WarnsAboutUnresolvedLobesAndSkippedSubareas) {
    const ss::GaussianAcv wide(0.05, 10.0);
    const hm::HeightMap map = ss::synthesize_surface(wide, {256, 256, 0.1}, 2);
    const auto coarse = sr::kirchhoff_brdf(map, Conductor::perfect(), options(550, 10, 3.2));
    EXPECT_TRUE(has_warning(coarse, "too small to resolve it")) << coarse.warnings.size();
    std::vector<std::uint8_t> validity(256 * 256, 1);
    validity[3] = 0;  // in the first of the 64 sub-areas
    const hm::HeightMap holed(256, 256, 0.1, 0.1, map.heights(), validity, "holed");
    const auto skipped = sr::kirchhoff_brdf(holed, Conductor::perfect(), options(550, 10, 3.2));
    EXPECT_EQ(skipped.subareas, 63u);
    EXPECT_TRUE(has_warning(skipped, "1 of 64 sub-areas hold invalid points"));
    const ss::GaussianAcv narrow(0.05, 1.0);  // lobe ~ lambda / (pi l) = 0.18: 8 steps of 25.6 um sub-areas
    const hm::HeightMap resolved = ss::synthesize_surface(narrow, {512, 512, 0.1}, 2);
    const auto fine = sr::kirchhoff_brdf(resolved, Conductor::perfect(), options(550, 10, 25.6));
    EXPECT_TRUE(fine.warnings.empty()) << fine.warnings.front();
}

// An interrupted run returns what it has: here nothing, since the request comes before the first sub-area.
TEST(KirchhoffMap, InterruptReturnsTheSubareasDone) {
    const hm::HeightMap flat(64, 64, 0.1, 0.1, std::vector<double>(64 * 64, 0.0), "flat");
    surfscatter::request_interrupt();
    const auto r = sr::kirchhoff_brdf(flat, Conductor::perfect(), options(550, 0, 3.2));
    surfscatter::clear_interrupt();
    EXPECT_EQ(r.subareas, 4u);
    EXPECT_EQ(r.subareas_done, 0u);
    EXPECT_EQ(r.albedo, 0.0);
}

}  // namespace
