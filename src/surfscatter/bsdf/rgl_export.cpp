#include "surfscatter/bsdf/rgl_export.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <random>
#include <thread>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/core/resources.hpp"
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

void check(bool ok, const std::string& name, const char* range) {
    if (!ok) fail("{} must be in {}", name, range);
}

}  // namespace

SpecularAsLobe::SpecularAsLobe(const Bsdf& model, double width_rad, const std::string& name)
    : model_(model), kappa_(1 / (width_rad * width_rad)),
      norm_(kappa_ / (kTwoPi * -std::expm1(-2 * kappa_))) {
    if (!(width_rad > 0 && width_rad < 0.2))
        fail("{} must be in (0, {:.3g}) degrees, got {:.6g}", name, 0.2 / kDegree, width_rad / kDegree);
    bool has_delta = false;
    for (int t = 0; t < 90 && !has_delta; ++t)
        has_delta = model.delta_reflectance(spherical_direction(t * kDegree, 0), 550) > 0;
    if (!has_delta) fail("{}: the model {} has no coherent specular part", name, model.name());
}

double SpecularAsLobe::eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const {
    const double f = model_.eval(wi, wo, lambda_nm);
    if (wi.z <= 0 || wo.z <= 0) return f;
    const double c = -wi.x * wo.x - wi.y * wo.y + wi.z * wo.z;  // cosine to the mirror direction
    const double kernel = norm_ * std::exp(kappa_ * (c - 1));
    return kernel > 0 ? f + model_.delta_reflectance(wi, lambda_nm) * kernel / wo.z : f;
}

std::optional<BsdfSample> SpecularAsLobe::sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const {
    auto s = model_.sample(wi, lambda_nm, u_lobe, u);
    if (s && s->delta) s->delta = false;  // the mirror direction, now the lobe's peak
    return s;
}

DeltaTable delta_table(const Bsdf& model, const std::vector<double>& theta_deg, const std::vector<double>& lambda_nm) {
    DeltaTable t{theta_deg, lambda_nm, {}};
    for (double th : theta_deg)
        for (double l : lambda_nm) t.reflectance.push_back(model.delta_reflectance(spherical_direction(th * kDegree, 0), l));
    return t;
}

namespace {

// The comparison of rgl_accuracy, one incidence at a time.
class AccuracyProbe {
public:
    AccuracyProbe(const Bsdf& model, const Bsdf& file, const std::vector<double>& lambda_nm, bool rgb, int directions,
                  double mirror_exclusion_rad = 0)
        : model_(model), file_(file), lambdas_(lambda_nm), rgb_(rgb), directions_(directions),
          mirror_cos_(mirror_exclusion_rad > 0 ? std::cos(mirror_exclusion_rad) : 2.0), rng_(35) {
        if (rgb) {
            lambdas_.clear();
            for (double l = 360; l <= 830 + 1e-9; l += 10) lambdas_.push_back(l);
            weights_ = colour_weights(lambdas_);
        }
        acc_.jump_band = model.jump_radius(lambdas_.front()) > 0 ? kRglJumpBand : 0.0;
    }
    double uniform() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng_); }

    // Compares at incidence wi; returns the worst relative error there.
    double compare(const Vec3& wi) {
        constexpr double kFloor = 0.01, kMaxThetaO = 80.0;
        std::vector<Vec3> wos{{-wi.x, -wi.y, wi.z}};
        for (int k = 0; k < directions_; ++k) {
            const double z = uniform(), r = std::sqrt(std::max(0.0, 1 - z * z)), phi = kTwoPi * uniform();
            wos.push_back({r * std::cos(phi), r * std::sin(phi), z});
            const auto drawn = model_.sample(wi, lambdas_[lambdas_.size() / 2], uniform(), {uniform(), uniform()});
            if (drawn && !drawn->delta) wos.push_back(drawn->wo);
        }
        double worst_here = 0;
        for (std::size_t k = 0; k < (rgb_ ? 1 : lambdas_.size()); ++k) {
            std::vector<double> f(wos.size());
            double peak = 0;
            // The peak outside the excluded core, so that the floor is relative to what is compared.
            for (std::size_t j = 0; j < wos.size(); ++j)
                if (dot(wos[j], wos[0]) <= mirror_cos_) peak = std::max(peak, f[j] = value(model_, wi, wos[j], k));
            for (std::size_t j = 0; j < wos.size(); ++j) {
                if (dot(wos[j], wos[0]) > mirror_cos_ || !(f[j] >= kFloor * peak && f[j] > 0) ||
                    wos[j].z < std::cos(kMaxThetaO * kDegree))
                    continue;
                const double e = std::abs(value(file_, wi, wos[j], k) / f[j] - 1);
                if (on_jump(wi, wos[j], k)) {
                    ++acc_.jump_compared;
                    acc_.jump_worst = std::max(acc_.jump_worst, e);
                    continue;
                }
                sum_sq_ += e * e;
                ++acc_.compared;
                worst_here = std::max(worst_here, e);
                if (e <= acc_.worst) continue;
                acc_.worst = e;
                acc_.theta_i_deg = rgl_elevation(wi) / kDegree, acc_.phi_i_deg = std::atan2(wi.y, wi.x) / kDegree;
                acc_.theta_o_deg = rgl_elevation(wos[j]) / kDegree;
                acc_.phi_o_deg = std::atan2(wos[j].y, wos[j].x) / kDegree;
                acc_.lambda_nm = rgb_ ? 0.0 : lambdas_[k];
            }
        }
        return worst_here;
    }
    RglAccuracy result() const {
        RglAccuracy a = acc_;
        a.rms = a.compared ? std::sqrt(sum_sq_ / double(a.compared)) : 0.0;
        return a;
    }

private:
    // Whether wo is within kRglJumpBand of the circle on which the model jumps (Bsdf::jump_radius, in the distance q
    // of the projected wo from the specular point); rgb: of any of the colour sums' wavelengths.
    bool on_jump(const Vec3& wi, const Vec3& wo, std::size_t k) const {
        if (acc_.jump_band == 0) return false;
        const double q = std::hypot(wo.x + wi.x, wo.y + wi.y);
        const double lo = model_.jump_radius(rgb_ ? lambdas_.front() : lambdas_[k]);
        const double hi = model_.jump_radius(rgb_ ? lambdas_.back() : lambdas_[k]);
        return q > (1 - kRglJumpBand) * std::min(lo, hi) && q < (1 + kRglJumpBand) * std::max(lo, hi);
    }
    double value(const Bsdf& b, const Vec3& wi, const Vec3& wo, std::size_t k) const {
        if (!rgb_) return b.eval(wi, wo, lambdas_[k]);
        double y = 0;
        for (std::size_t j = 0; j < lambdas_.size(); ++j) y += weights_[j].y * b.eval(wi, wo, lambdas_[j]);
        return y;
    }
    const Bsdf& model_;
    const Bsdf& file_;
    std::vector<double> lambdas_;
    std::vector<Vec3> weights_;
    bool rgb_;
    int directions_;
    double mirror_cos_;  // directions closer than this to the mirror direction are not compared
    std::mt19937_64 rng_;
    RglAccuracy acc_;
    double sum_sq_ = 0;
};

}  // namespace

RglAccuracy rgl_accuracy(const Bsdf& model, const RglMeasuredBsdf& file, double theta_i_max_deg,
                         const std::vector<double>& lambda_nm, bool rgb, int incidences, int directions,
                         double mirror_exclusion_rad) {
    AccuracyProbe probe(model, file, lambda_nm, rgb, directions, mirror_exclusion_rad);
    for (int n = 0; n < incidences; ++n) {
        const double theta_i = theta_i_max_deg * probe.uniform() * kDegree;
        const double phi_i = (2 * probe.uniform() - 1) * kPi;
        probe.compare(spherical_direction(theta_i, model.isotropic() ? 0.0 : phi_i));
    }
    return probe.result();
}

RglAccuracy rgl_file_accuracy(const Bsdf& model, const std::filesystem::path& path, const RglExportOptions& o) {
    const RglData data = read_rgl(path);
    const RglMeasuredBsdf file(data);
    std::vector<double> lambdas;
    if (!data.rgb) lambdas = {data.wavelengths.front(), o.reference_lambda_nm, data.wavelengths.back()};
    return rgl_accuracy(model, file, o.theta_i_max_deg, lambdas, data.rgb, 24, 256, o.mirror_exclusion_rad);
}

std::string rgl_accuracy_where(const RglAccuracy& a) {
    return fmt::format("theta_i {:.1f} phi_i {:.1f} theta_o {:.1f} phi_o {:.1f} deg, {}", a.theta_i_deg, a.phi_i_deg,
                       a.theta_o_deg, a.phi_o_deg, a.lambda_nm > 0 ? fmt::format("{} nm", a.lambda_nm) : "CIE Y");
}

void check_rgl_accuracy(const RglAccuracy& a, double tolerance_percent, const std::string& option,
                        const std::string& path) {
    if (!(tolerance_percent > 0) || !std::isfinite(tolerance_percent))
        fail("{} must be a percentage > 0, got {}", option, tolerance_percent);
    if (100 * a.worst > tolerance_percent)
        fail("brdf export: the file {} differs from the model by up to {:.2f} % (at {}), more than {} {} %; finer "
             "incidence, sample or NDF resolution may bring it within (docs/MODELS.md \"Export to the RGL format\"), "
             "or a larger {} accepts it",
             printable(path, kShownPathChars), 100 * a.worst, rgl_accuracy_where(a), option, tolerance_percent, option);
}

namespace {

// Fills the VNDF, luminance and spectral (or rgb) tables of d for its theta_i x phi_i, the model evaluated at
// `lambda` (the file's wavelengths, or the colour sums' for rgb files).
void tabulate(const Bsdf& model, const RglExportOptions& o, const Marginal2D& ndf, const Marginal2D& sigma,
              const std::vector<double>& lambda, RglData& d) {
    const bool iso = d.isotropic();
    const std::size_t nt = static_cast<std::size_t>(o.ndf_resolution);
    std::vector<double> colour_lambda;
    std::vector<std::size_t> colour_index;
    for (std::size_t k = 0; k < lambda.size(); ++k)
        if (lambda[k] >= 360 && lambda[k] <= 830) colour_lambda.push_back(lambda[k]), colour_index.push_back(k);
    const auto weights = colour_weights(colour_lambda);
    // VNDF slices over u_m = (u_theta, u_phi): the warp that places the sample nodes. The format lets each incidence
    // have its own (readers only invert it); the standard D(m) <wi, m>+ / sigma(wi) * 2 pi^2 u sin(theta_m) puts too
    // few nodes where the lobe at this incidence differs from D (a spike narrower at oblique incidence than at
    // retro-reflection; the tail toward the horizon), so each slice mixes a share kStandardShare of it with the square
    // root of the lobe's own density in u_m at the reference wavelength, f cos(theta_o) * 4 <wi, m> * 2 pi^2 u
    // sin(theta_m), each normalised. Shares and power measured (docs/MODELS.md "Export to the RGL format").
    constexpr double kStandardShare = 0.1;
    const std::size_t nphi_i = d.phi_i.size(), ntheta_i = d.theta_i.size();
    d.vndf_rows = nt, d.vndf_cols = nt;
    d.vndf.assign(nphi_i * ntheta_i * nt * nt, 0.0);
    parallel_for(static_cast<int>(nphi_i * ntheta_i), o.threads, [&](int job) {
        const std::size_t a = std::size_t(job) / ntheta_i, b = std::size_t(job) % ntheta_i;
        const Vec3 wi = spherical_direction(d.theta_i[b], d.phi_i[a]);
        const double s = sigma.eval({rgl_theta_to_u(d.theta_i[b]), rgl_phi_to_u(d.phi_i[a])});
        double* slice = d.vndf.data() + std::size_t(job) * nt * nt;
        std::vector<double> lobe(nt * nt, 0.0);
        double standard_sum = 0, lobe_sum = 0;
        for (std::size_t y = 0; y < nt; ++y)
            for (std::size_t x = 0; x < nt; ++x) {
                const double ux = double(x) / double(nt - 1), uy = double(y) / double(nt - 1);
                const double theta = rgl_u_to_theta(ux), phi = rgl_u_to_phi(uy) + (iso ? d.phi_i[a] : 0.0);
                const Vec3 m = spherical_direction(theta, phi);
                const double wi_m = dot(wi, m), area = 2 * kPi * kPi * ux * std::sin(theta);
                const std::size_t i = y * nt + x;
                slice[i] = ndf.eval({ux, uy}) * std::max(0.0, wi_m) / s * area;
                const Vec3 wo = m * (2 * wi_m) - wi;
                if (wi_m > 0 && wo.z > 0)
                    lobe[i] = std::sqrt(std::max(0.0, model.eval(wi, wo, o.reference_lambda_nm) * wo.z * 4 * wi_m * area));
                standard_sum += slice[i];
                lobe_sum += lobe[i];
            }
        if (lobe_sum > 0)
            for (std::size_t i = 0; i < nt * nt; ++i)
                slice[i] = kStandardShare * slice[i] / standard_sum + (1 - kStandardShare) * lobe[i] / lobe_sum;
    });
    const Marginal2D vndf(d.vndf, nt, nt, {d.phi_i, d.theta_i}, true);

    // Spectral (or rgb) and luminance tables at the nodes of the sample square.
    const std::size_t ns = static_cast<std::size_t>(o.sample_resolution), plane = ns * ns;
    d.rows = ns, d.cols = ns;
    const std::size_t channels = d.rgb ? 3 : lambda.size();
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
            const auto [u_m, vndf_pdf] = vndf.sample(sample, params);
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
            // Sampling draws the sample point from the luminance table, then u_m from the VNDF warp: the density in
            // wo is luminance(sample) vndf_pdf(u_m) / (2 pi^2 u sin(theta_m) 4 <wi, m>), proportional to Y(f cos) when
            // the luminance table holds Y(f cos) 2 pi^2 u sin(theta_m) 4 <wi, m> / vndf_pdf (with the standard warp,
            // the Y of the spectral table).
            const double area = 2 * kPi * kPi * u_m.x * std::sin(theta_m) * 4 * dot(wi, m);
            d.luminance[slice * plane + i] = vndf_pdf > 0 ? std::max(0.0, rgb_xyz.y) / factor * wo.z * area / vndf_pdf : 0.0;
            if (d.rgb) {
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
}

// Adds incidences (theta_i nodes) at the midpoint of every interval where the file, tabulated at its first, reference
// and last wavelengths, misses the model there by more than o.tolerance_percent: where the lobe changes shape faster
// with theta_i (toward grazing incidence, narrow spikes) than interpolation between slices follows. Up to
// kMaxRglRefinedIncidences nodes, in rounds that halve the intervals still failing.
void refine_incidences(const Bsdf& model, const RglExportOptions& o, const Marginal2D& ndf, const Marginal2D& sigma,
                       const std::vector<double>& lambda, RglData& d) {
    std::vector<double> check{lambda.front(), o.reference_lambda_nm, lambda.back()};
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    std::vector<double> azimuths{0.0};
    if (!d.isotropic())
        for (int k = 1; k < 4; ++k) azimuths.push_back(-kPi + kTwoPi * (k + 0.5) / 4);
    while (d.theta_i.size() < kMaxRglRefinedIncidences) {
        RglData trial = d;
        trial.rgb = false;
        trial.wavelengths = check;
        tabulate(model, o, ndf, sigma, check, trial);
        const RglMeasuredBsdf file(trial);
        AccuracyProbe probe(model, file, check, false, 64, o.mirror_exclusion_rad);
        std::vector<double> nodes;
        for (std::size_t k = 0; k < d.theta_i.size(); ++k) {
            nodes.push_back(d.theta_i[k]);
            if (k + 1 == d.theta_i.size() || nodes.size() + (d.theta_i.size() - k) > kMaxRglRefinedIncidences) continue;
            const double mid = 0.5 * (d.theta_i[k] + d.theta_i[k + 1]);
            double worst = 0;
            for (double phi : azimuths) worst = std::max(worst, probe.compare(spherical_direction(mid, phi)));
            if (100 * worst > o.tolerance_percent) nodes.push_back(mid);
        }
        if (nodes.size() == d.theta_i.size()) break;
        d.theta_i = nodes;
    }
}

}  // namespace

std::vector<double> rgl_export_wavelengths(const RglExportOptions& o) {
    std::vector<double> lambda;
    const int n = static_cast<int>(std::ceil((o.lambda_max_nm - o.lambda_min_nm) / o.lambda_step_nm - 1e-9)) + 1;
    for (int k = 0; k < n; ++k) lambda.push_back(std::min(o.lambda_max_nm, o.lambda_min_nm + o.lambda_step_nm * k));
    return lambda;
}

double rgl_export_bytes(const RglExportOptions& o, bool isotropic, std::size_t incidences) {
    const double slices = double(incidences) * (isotropic ? 1.0 : double(o.phi_i_count));
    const double channels = o.rgb ? 3.0 : double(rgl_export_wavelengths(o).size());
    const double ns = o.sample_resolution, nt = o.ndf_resolution, np = isotropic ? 2.0 : nt;
    // float32 spectra (or rgb) and luminance at ns^2 nodes, the VNDF at nt^2, NDF and sigma; one valid bit per node.
    return 4 * (slices * ((channels + 1) * ns * ns + nt * nt) + 2 * np * nt) + slices * ns * ns / 8;
}

void check_rgl_export_options(const RglExportOptions& o, bool isotropic) {
    check(o.theta_i_count >= 2 && o.theta_i_count <= 256, o.names.theta_i_count, "2..256");
    check(o.theta_i_max_deg > 0 && o.theta_i_max_deg < 90, "theta_i_max_deg", "(0, 90) degrees");
    check(o.phi_i_count >= 3 && o.phi_i_count <= 256, o.names.phi_i_count, "3..256");  // 2 reads as isotropic
    check(o.ndf_resolution >= 8 && o.ndf_resolution <= 1024, o.names.ndf_resolution, "8..1024");
    check(o.sample_resolution >= 4 && o.sample_resolution <= 512, o.names.sample_resolution, "4..512");
    if (!(o.lambda_min_nm > 0 && o.lambda_max_nm > o.lambda_min_nm && std::isfinite(o.lambda_max_nm)))
        fail("the spectral grid needs 0 < lambda_min < lambda_max, got {} and {} nm", o.lambda_min_nm, o.lambda_max_nm);
    if (!o.rgb && !(o.lambda_step_nm >= kMinRglLambdaStepNm && o.lambda_step_nm <= o.lambda_max_nm - o.lambda_min_nm))
        fail("{} must be in [{}, {}] nm, got {}", o.names.lambda_step, kMinRglLambdaStepNm,
             o.lambda_max_nm - o.lambda_min_nm, o.lambda_step_nm);
    const std::size_t most = o.tolerance_percent > 0
                                 ? std::max(kMaxRglRefinedIncidences, static_cast<std::size_t>(o.theta_i_count))
                                 : static_cast<std::size_t>(o.theta_i_count);
    // The tables in double (twice the file), the refinement's trial copy of them, and the file read back.
    const double file = rgl_export_bytes(o, isotropic, most), bytes = file * (o.tolerance_percent > 0 ? 5 : 3);
    const double available = static_cast<double>(available_memory_bytes());
    if (bytes > available)
        fail("brdf export: a file of {} ({} incidences{}, {} x {} samples, {} channels) needs {} of memory, more than "
             "the {} available: use a smaller {} or {}{}{}",
             format_bytes(file), most, isotropic ? "" : fmt::format(" x {} azimuths", o.phi_i_count),
             o.sample_resolution, o.sample_resolution, o.rgb ? 3 : rgl_export_wavelengths(o).size(),
             format_bytes(bytes), format_bytes(available), o.names.sample_resolution, o.names.theta_i_count,
             isotropic ? "" : fmt::format(", {}", o.names.phi_i_count),
             o.rgb ? "" : fmt::format(" or a larger {}", o.names.lambda_step));
}

RglData export_rgl(const Bsdf& model, const RglExportOptions& o, const std::string& description) {
    check_rgl_export_options(o, model.isotropic());
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
        // The full circle: pbrt-v4 refuses files folded by a symmetry (its reader stops on a reduction other than 1).
        for (int k = 0; k < o.phi_i_count; ++k) d.phi_i.push_back(-kPi + kTwoPi * k / (o.phi_i_count - 1));
    }
    // Wavelengths the model is evaluated at: the file's (spectral) or the colour sums' (rgb, 5 nm over 360-830).
    std::vector<double> lambda;
    if (o.rgb) {
        for (double l = 360; l <= 830 + 1e-9; l += 5) lambda.push_back(l);
    } else {
        lambda = rgl_export_wavelengths(o);
        d.wavelengths = lambda;
    }
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

    if (o.tolerance_percent > 0) refine_incidences(model, o, ndf, sigma, lambda, d);
    tabulate(model, o, ndf, sigma, lambda, d);
    d.valid.assign((d.phi_i.size() * d.theta_i.size() * d.rows * d.cols + 7) / 8, '\xff');
    return d;
}

}  // namespace surfscatter::bsdf
