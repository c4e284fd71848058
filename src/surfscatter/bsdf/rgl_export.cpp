#include "surfscatter/bsdf/rgl_export.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/marginal_2d.hpp"
#include "surfscatter/math/quadrature.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::bsdf {

namespace {

// Runs f(k) for k in [0, n) on `threads` threads; the first exception is rethrown.
template <typename F>
void parallel_for(int n, int threads, F f) {
    if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    threads = std::min(threads, n);
    std::atomic<int> next{0};
    std::exception_ptr error;
    std::mutex mutex;
    auto work = [&] {
        for (int k; (k = next++) < n;) {
            try {
                f(k);
            } catch (...) {
                std::lock_guard lock(mutex);
                if (!error) error = std::current_exception();
                next = n;
            }
        }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    if (error) std::rethrow_exception(error);
}

// Linear sRGB (and Y) per unit reflectance at each wavelength under D65, for sums over an even wavelength grid.
std::vector<Vec3> colour_weights(const std::vector<double>& lambda) {
    const auto& cmf = spectrum::cie1931();
    const auto& d65 = spectrum::cie_illuminant("D65");
    std::vector<Vec3> w(lambda.size());
    double y_total = 0;
    for (std::size_t k = 0; k < lambda.size(); ++k) {
        const double weight = (k == 0 || k + 1 == lambda.size() ? 0.5 : 1.0) * d65(lambda[k]);  // trapezoid
        w[k] = cmf.xyz_bar(lambda[k]) * weight;
        y_total += w[k].y;
    }
    for (auto& v : w) v = v * (1.0 / y_total);
    return w;
}

void check(bool ok, const char* what) {
    if (!ok) fail("{}", what);
}

}  // namespace

DeltaTable delta_table(const Bsdf& model, const std::vector<double>& theta_deg, const std::vector<double>& lambda_nm) {
    DeltaTable t{theta_deg, lambda_nm, {}};
    for (double th : theta_deg)
        for (double l : lambda_nm) t.reflectance.push_back(model.delta_reflectance(spherical_direction(th * kDegree, 0), l));
    return t;
}

RglData export_rgl(const Bsdf& model, const RglExportOptions& o, const std::string& description) {
    check(o.theta_i_count >= 2 && o.theta_i_count <= 256, "--theta-i-count must be in 2..256");
    check(o.theta_i_max_deg > 0 && o.theta_i_max_deg < 90, "--theta-i-max must be in (0, 90) degrees");
    check(o.phi_i_count >= 2 && o.phi_i_count <= 256, "--phi-i-count must be in 2..256");
    check(o.ndf_resolution >= 8 && o.ndf_resolution <= 1024, "--ndf-resolution must be in 8..1024");
    check(o.sample_resolution >= 4 && o.sample_resolution <= 512, "--sample-resolution must be in 4..512");
    check(o.lambda_step_nm > 0 && o.lambda_min_nm > 0 && o.lambda_max_nm > o.lambda_min_nm,
          "the spectral grid needs 0 < lambda_min < lambda_max and a step > 0");
    const bool iso = model.isotropic();
    RglData d;
    d.description = description;
    d.jacobian = true;
    d.rgb = o.rgb;
    for (int k = 0; k < o.theta_i_count; ++k)
        d.theta_i.push_back(o.theta_i_max_deg * kDegree * k / (o.theta_i_count - 1));
    if (iso) {
        d.phi_i = {0.0};
    } else {
        for (int k = 0; k < o.phi_i_count; ++k) d.phi_i.push_back(-kPi + kPi * k / (o.phi_i_count - 1));
    }
    // Wavelengths the model is evaluated at: the file's (spectral) or the colour sums' (rgb, 5 nm over 360-830).
    std::vector<double> lambda;
    if (o.rgb) {
        for (double l = 360; l <= 830 + 1e-9; l += 5) lambda.push_back(l);
    } else {
        const int n = static_cast<int>(std::ceil((o.lambda_max_nm - o.lambda_min_nm) / o.lambda_step_nm - 1e-9)) + 1;
        for (int k = 0; k < n; ++k) lambda.push_back(std::min(o.lambda_max_nm, o.lambda_min_nm + o.lambda_step_nm * k));
        d.wavelengths = lambda;
    }
    std::vector<double> colour_lambda;
    std::vector<std::size_t> colour_index;
    for (std::size_t k = 0; k < lambda.size(); ++k)
        if (lambda[k] >= 360 && lambda[k] <= 830) colour_lambda.push_back(lambda[k]), colour_index.push_back(k);
    const auto weights = colour_weights(colour_lambda);
    for (double l : lambda) model.eval({0, 0, 1}, {0, 0, 1}, l);  // a wavelength the material lacks fails first

    // NDF from retro-reflection, floored at 1e-4 of its peak so that every half vector keeps a finite weight.
    const std::size_t nt = static_cast<std::size_t>(o.ndf_resolution);
    const std::size_t np = iso ? 2 : nt;
    d.ndf_rows = np, d.ndf_cols = nt;
    d.ndf.assign(np * nt, 0.0);
    for (std::size_t r = 0; r < np; ++r)
        for (std::size_t c = 0; c < nt; ++c) {
            const double theta = std::min(rgl_u_to_theta(double(c) / double(nt - 1)), 89.5 * kDegree);
            const double phi = iso ? 0.0 : rgl_u_to_phi(double(r) / double(np - 1));
            const Vec3 m = spherical_direction(theta, phi);
            d.ndf[r * nt + c] = std::max(0.0, model.eval(m, m, o.reference_lambda_nm)) * m.z * m.z;
        }
    const double peak = *std::max_element(d.ndf.begin(), d.ndf.end());
    if (!(peak > 0)) fail("brdf export: the model's retro-reflection is 0 everywhere at {} nm", o.reference_lambda_nm);
    for (double& v : d.ndf) v = std::max(v, 1e-4 * peak);
    const Marginal2D ndf_raw(d.ndf, nt, np, {}, false);
    // Projected area of the NDF's own interpolant: 3-node Gauss-Legendre per u cell, 128 azimuth midpoints (sigma
    // only shapes the sampling density and cancels from f: the exported f uses the reader's own interpolated sigma).
    const math::GaussLegendreRule rule(3);
    auto projected = [&](const Vec3& wi) {
        constexpr int kAzimuths = 128;
        double sum = 0;
        for (std::size_t cell = 0; cell + 1 < nt; ++cell)
            for (std::size_t a = 0; a < rule.nodes.size(); ++a) {
                const double u = (double(cell) + 0.5 + 0.5 * rule.nodes[a]) / double(nt - 1);
                const double theta = rgl_u_to_theta(u);
                double ring = 0;
                for (int b = 0; b < kAzimuths; ++b) {
                    const double uphi = (b + 0.5) / kAzimuths;
                    ring += ndf_raw.eval({u, uphi}) * std::max(0.0, dot(wi, spherical_direction(theta, rgl_u_to_phi(uphi))));
                }
                sum += rule.weights[a] * 0.5 / double(nt - 1) * ring * (kTwoPi / kAzimuths) * std::sin(theta) * u * kPi;
            }
        return sum;
    };
    const double norm = projected({0, 0, 1});
    for (double& v : d.ndf) v /= norm;
    const Marginal2D ndf(d.ndf, nt, np, {}, false);
    d.sigma_rows = np, d.sigma_cols = nt;
    d.sigma.assign(np * nt, 0.0);
    parallel_for(static_cast<int>(np * nt), o.threads, [&](int k) {
        const std::size_t r = std::size_t(k) / nt, c = std::size_t(k) % nt;
        if (iso && r == 1) return;
        const double theta = rgl_u_to_theta(double(c) / double(nt - 1));
        const double phi = iso ? 0.0 : rgl_u_to_phi(double(r) / double(np - 1));
        d.sigma[r * nt + c] = std::max(projected(spherical_direction(theta, phi)) / norm, 1e-6);
    });
    if (iso) std::copy(d.sigma.begin(), d.sigma.begin() + long(nt), d.sigma.begin() + long(nt));
    const Marginal2D sigma(d.sigma, nt, np, {}, false);

    // VNDF slices over u_m = (u_theta, u_phi), density D(m) <wi, m>+ / sigma(wi) * 2 pi^2 u sin(theta_m).
    const std::size_t nphi_i = d.phi_i.size(), ntheta_i = d.theta_i.size();
    d.vndf_rows = nt, d.vndf_cols = nt;
    d.vndf.assign(nphi_i * ntheta_i * nt * nt, 0.0);
    for (std::size_t a = 0; a < nphi_i; ++a)
        for (std::size_t b = 0; b < ntheta_i; ++b) {
            const Vec3 wi = spherical_direction(d.theta_i[b], d.phi_i[a]);
            const double s = sigma.eval({rgl_theta_to_u(d.theta_i[b]), rgl_phi_to_u(d.phi_i[a])});
            double* slice = d.vndf.data() + (a * ntheta_i + b) * nt * nt;
            for (std::size_t y = 0; y < nt; ++y)
                for (std::size_t x = 0; x < nt; ++x) {
                    const double ux = double(x) / double(nt - 1), uy = double(y) / double(nt - 1);
                    const double theta = rgl_u_to_theta(ux), phi = rgl_u_to_phi(uy) + (iso ? d.phi_i[a] : 0.0);
                    const Vec3 m = spherical_direction(theta, phi);
                    slice[y * nt + x] = ndf.eval({ux, uy}) *
                                        std::max(0.0, dot(wi, m)) / s * 2 * kPi * kPi * ux * std::sin(theta);
                }
        }
    const Marginal2D vndf(d.vndf, nt, nt, {d.phi_i, d.theta_i}, true);

    // Spectral (or rgb) and luminance tables at the nodes of the sample square.
    const std::size_t ns = static_cast<std::size_t>(o.sample_resolution), plane = ns * ns;
    d.rows = ns, d.cols = ns;
    const std::size_t channels = o.rgb ? 3 : lambda.size();
    d.spectra.assign(nphi_i * ntheta_i * channels * plane, 0.0);
    d.luminance.assign(nphi_i * ntheta_i * plane, 0.0);
    parallel_for(static_cast<int>(nphi_i * ntheta_i * ns), o.threads, [&](int job) {
        const std::size_t slice = std::size_t(job) / ns, y = std::size_t(job) % ns;
        const std::size_t a = slice / ntheta_i, b = slice % ntheta_i;
        const Vec3 wi = spherical_direction(d.theta_i[b], d.phi_i[a]);
        const double params[2] = {d.phi_i[a], d.theta_i[b]};
        const double s = sigma.eval({rgl_theta_to_u(d.theta_i[b]), rgl_phi_to_u(d.phi_i[a])});
        std::vector<double> f(lambda.size());
        for (std::size_t x = 0; x < ns; ++x) {
            const Vec2 sample{double(x) / double(ns - 1), double(y) / double(ns - 1)};
            const Vec2 u_m = vndf.sample(sample, params).first;
            const double theta_m = rgl_u_to_theta(u_m.x);
            const double phi_m = rgl_u_to_phi(u_m.y) + (iso ? d.phi_i[a] : 0.0);
            const Vec3 m = spherical_direction(theta_m, phi_m);
            const Vec3 wo = normalize(m * (2 * dot(wi, m)) - wi);
            const std::size_t i = y * ns + x;
            if (wo.z <= 1e-9 || dot(wi, m) <= 0) continue;  // below the horizon: the reader's f is 0 there too
            const double factor = wo.z * 4 * s / ndf.eval(u_m);
            for (std::size_t k = 0; k < lambda.size(); ++k) f[k] = model.eval(wi, wo, lambda[k]) * factor;
            Vec3 rgb_xyz{0, 0, 0};
            for (std::size_t k = 0; k < colour_lambda.size(); ++k) rgb_xyz = rgb_xyz + weights[k] * f[colour_index[k]];
            d.luminance[slice * plane + i] = std::max(0.0, rgb_xyz.y);
            if (o.rgb) {
                const Vec3 rgb = spectrum::xyz_to_linear_srgb(rgb_xyz);
                const double c[3] = {rgb.x, rgb.y, rgb.z};
                for (std::size_t ch = 0; ch < 3; ++ch) d.spectra[(slice * 3 + ch) * plane + i] = std::max(0.0, c[ch]);
            } else {
                for (std::size_t k = 0; k < lambda.size(); ++k) d.spectra[(slice * lambda.size() + k) * plane + i] = f[k];
            }
        }
    });
    // A luminance slice that is 0 everywhere (a model without reflection there) cannot be sampled: make it uniform.
    for (std::size_t slice = 0; slice < nphi_i * ntheta_i; ++slice) {
        double* l = d.luminance.data() + slice * plane;
        if (*std::max_element(l, l + plane) <= 0) std::fill(l, l + plane, 1.0);
    }
    d.valid.assign((nphi_i * ntheta_i * plane + 7) / 8, '\xff');
    return d;
}

}  // namespace surfscatter::bsdf
