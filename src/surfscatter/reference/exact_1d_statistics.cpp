#include "surfscatter/reference/exact_1d_statistics.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

#include <fmt/format.h>

#include "surfscatter/core/error.hpp"
#include "surfscatter/math/vec.hpp"
#include "surfscatter/reference/far_field_sum.hpp"
#include "surfscatter/core/resources.hpp"
#include "surfscatter/reference/parallel_jobs.hpp"
#include "surfscatter/surface/synthesis.hpp"

namespace surfscatter::reference {

namespace {

using Complex = std::complex<double>;

// The control variate (docs/REFERENCE.md, "Statistical mode"): the Kirchhoff far field of the profile's samples
// under the beam's footprint,
//   b(theta) = sum_j rho_j exp(-i (k sin(theta) x_j + q_z h_j)),  rho_j = exp(-x_j^2/g^2) e^{i k sin(theta_i) x_j} dx,
// q_z = k (cos theta_i + cos theta). The synthesised heights are jointly Gaussian with the periodic covariance
// C_m = sum over the synthesis's lines of P1(|zeta|) dzeta cos(zeta m dx) (s^2 = C_0), so
//   E b = e^{-q_z^2 s^2 / 2} sum_j rho_j e^{-i k sin(theta) x_j},
//   E|b - E b|^2 = e^{-q_z^2 s^2} sum_m R_m e^{-i k sin(theta) m dx} expm1(q_z^2 C_m),  R_m = sum_l rho_{l+m} conj(rho_l),
// exactly (to rounding). On a smooth surface b - E b is the first-order perturbation far field up to a factor per
// direction, on a rough one the tangent-plane field: correlated with the exact a in both regimes.
class KirchhoffControl {
public:
    KirchhoffControl(const surface::RadialStatistics& statistics, const Exact1dOptions& options, const Profile& grid)
        : k_(kTwoPi / (options.lambda_nm * 1e-3)), cos_i_(std::cos(options.theta_i_rad)), x0_(grid.x0_um),
          step_(grid.spacing_um), rho_(grid.h_um.size()) {
        const std::size_t n = grid.h_um.size();
        const double alpha = k_ * std::sin(options.theta_i_rad), g = options.beam_width_um;
        std::vector<double> taper(n);
        for (std::size_t j = 0; j < n; ++j) {
            const double x = x0_ + step_ * static_cast<double>(j);
            taper[j] = std::exp(-x * x / (g * g)) * step_;
            rho_[j] = std::polar(taper[j], alpha * x);
        }
        // The synthesis's line variances P1 dzeta at zeta_q = q dzeta, q = 0 .. n/2 (q and -q both present except
        // q = 0 and, for even n, q = n/2), and the covariance C_m from a cosine table over the period.
        const double dzeta = kTwoPi / (static_cast<double>(n) * step_);
        std::vector<double> line(n / 2 + 1);
        for (std::size_t q = 0; q < line.size(); ++q) {
            const double weight = (q == 0 || 2 * q == n) ? 1.0 : 2.0;
            line[q] = weight * surface::profile_psd(statistics, static_cast<double>(q) * dzeta) * dzeta;
        }
        std::vector<double> cosine(n), covariance(n, 0.0), autocorrelation(n, 0.0);
        for (std::size_t j = 0; j < n; ++j) cosine[j] = std::cos(kTwoPi * static_cast<double>(j) / static_cast<double>(n));
        for (std::size_t m = 0; m < n; ++m) {
            for (std::size_t q = 0; q < line.size(); ++q) covariance[m] += line[q] * cosine[(q * m) % n];
            for (std::size_t l = 0; l + m < n; ++l) autocorrelation[m] += taper[l + m] * taper[l];
        }
        const double s2 = covariance[0];
        const std::vector<Complex> flat = far_field_sum(k_, x0_, step_, std::vector<double>(n, 0.0), rho_, {}, {});
        mean.resize(flat.size());
        variance.resize(flat.size());
        for (std::size_t d = 0; d < flat.size(); ++d) {
            const double theta = (-90.0 + 180.0 * static_cast<double>(d) / kFarFieldSteps) * kDegree;
            const double qz = k_ * (cos_i_ + std::cos(theta)), q2 = qz * qz;
            mean[d] = std::exp(-0.5 * q2 * s2) * flat[d];
            // R_m e^{-i k sin(theta) m dx} + its conjugate for -m: 2 R_m cos((alpha - k sin theta) m dx), by recurrence.
            const double shift = (alpha - k_ * std::sin(theta)) * step_;
            const double step_c = std::cos(shift), step_s = std::sin(shift);
            double c = 1.0, s = 0.0, sum = autocorrelation[0] * std::expm1(q2 * covariance[0]);
            for (std::size_t m = 1; m < n; ++m) {
                const double next = c * step_c - s * step_s;
                s = s * step_c + c * step_s;
                c = next;
                sum += 2.0 * autocorrelation[m] * c * std::expm1(q2 * covariance[m]);
            }
            variance[d] = std::exp(-q2 * s2) * sum;
        }
    }

    // b for one profile on the grid given to the constructor.
    std::vector<Complex> amplitude(const Profile& profile) const {
        std::vector<Complex> weights(rho_.size());
        for (std::size_t j = 0; j < rho_.size(); ++j) weights[j] = rho_[j] * std::polar(1.0, -k_ * cos_i_ * profile.h_um[j]);
        return far_field_sum(k_, x0_, step_, profile.h_um, weights, {}, {});
    }

    std::vector<Complex> mean;     // E b per direction
    std::vector<double> variance;  // E |b - E b|^2

private:
    double k_, cos_i_, x0_, step_;
    std::vector<Complex> rho_;
};

// Running means and co-moments (Welford's update) per direction of x = (|u|^2, Re u, Im u, |v|^2, Re v, Im v),
// u = a - a_first (centred on the first realization's amplitude, so that a strong coherent beam cancels no
// digits), v = b - E b. Every estimate below is an affine function of these moments.
class Moments {
public:
    explicit Moments(std::vector<Complex> control_mean) : control_mean_(std::move(control_mean)) {}

    void add(const std::vector<Complex>& a, const std::vector<Complex>& b) {
        const std::size_t m = a.size();
        if (count_ == 0) {
            centre_ = a;
            mean_.assign(m, {});
            co_.assign(m, {});
        }
        ++count_;
        const double inverse = 1.0 / static_cast<double>(count_);
        for (std::size_t d = 0; d < m; ++d) {
            const Complex u = a[d] - centre_[d], v = b[d] - control_mean_[d];
            const std::array<double, 6> x{std::norm(u), u.real(), u.imag(), std::norm(v), v.real(), v.imag()};
            std::array<double, 6> delta;
            for (int i = 0; i < 6; ++i) {
                delta[i] = x[i] - mean_[d][i];
                mean_[d][i] += delta[i] * inverse;
            }
            for (int i = 0; i < 6; ++i)
                for (int j = i; j < 6; ++j) co_[d][6 * i + j] += delta[i] * (x[j] - mean_[d][j]);
        }
    }

    std::size_t count() const { return count_; }
    const std::vector<Complex>& centre() const { return centre_; }
    const std::array<double, 6>& mean(std::size_t d) const { return mean_[d]; }
    // Sample covariance of components i and j.
    double covariance(std::size_t d, int i, int j) const {
        return co_[d][i <= j ? 6 * i + j : 6 * j + i] / static_cast<double>(count_ - 1);
    }

private:
    std::vector<Complex> control_mean_, centre_;
    std::vector<std::array<double, 6>> mean_;
    std::vector<std::array<double, 36>> co_;
    std::size_t count_ = 0;
};

// l1^T S l2 with S the sample covariance of x at direction d.
double bilinear(const Moments& moments, std::size_t d, const std::array<double, 6>& l1, const std::array<double, 6>& l2) {
    double sum = 0.0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) sum += l1[i] * l2[j] * moments.covariance(d, i, j);
    return sum;
}

StatisticalResult estimates(const Moments& moments, const KirchhoffControl& control, std::vector<double> theta) {
    StatisticalResult out;
    out.realizations = moments.count();
    const std::size_t m = theta.size();
    out.theta_o_rad = std::move(theta);
    for (auto* v : {&out.intensity, &out.coherent, &out.incoherent, &out.coherent_stderr, &out.incoherent_stderr,
                    &out.incoherent_plain, &out.incoherent_plain_stderr})
        v->assign(m, 0.0);
    if (moments.count() == 0) return out;
    const double n = static_cast<double>(moments.count());
    // The control's coefficients are fitted to the same samples: with p real coefficients the residual variance has
    // n - 1 - p degrees of freedom and the estimate's variance grows by (n - 2) / (n - 2 - p) (normal theory,
    // Lavenberg and Welch 1981); below kMinControlledRealizations the plain estimates are kept.
    const bool controlled = moments.count() >= kMinControlledRealizations;
    const auto inflation = [&](double p) { return controlled ? (n - 1) / (n - 1 - p) * (n - 2) / (n - 2 - p) : 1.0; };
    for (std::size_t d = 0; d < m; ++d) {
        const auto& mean = moments.mean(d);
        const Complex centre = moments.centre()[d], u(mean[1], mean[2]), v(mean[4], mean[5]);
        out.intensity[d] = mean[0] + 2.0 * (u * std::conj(centre)).real() + std::norm(centre);
        if (moments.count() < 2) {
            out.coherent[d] = out.intensity[d];
            continue;
        }
        // Incoherent: the sample variance I of a, with influence q = |u - <u>|^2, against that of b (w = |v -
        // <v>|^2) whose mean is known: I - beta (J - E J), beta = cov(q, w) / var(w) minimising the variance.
        const double plain = moments.covariance(d, 1, 1) + moments.covariance(d, 2, 2);
        const double spread = moments.covariance(d, 4, 4) + moments.covariance(d, 5, 5);
        const std::array<double, 6> q{1.0, -2.0 * u.real(), -2.0 * u.imag(), 0.0, 0.0, 0.0};
        const std::array<double, 6> w{0.0, 0.0, 0.0, 1.0, -2.0 * v.real(), -2.0 * v.imag()};
        const double var_q = bilinear(moments, d, q, q), var_w = bilinear(moments, d, w, w);
        const double cov_qw = bilinear(moments, d, q, w);
        const double beta = controlled && var_w > 0 ? cov_qw / var_w : 0.0;
        out.incoherent_plain[d] = plain;
        out.incoherent_plain_stderr[d] = std::sqrt(std::max(0.0, var_q) / n);
        out.incoherent[d] = plain - beta * (spread - control.variance[d]);
        out.incoherent_stderr[d] =
            std::sqrt(std::max(0.0, var_q - 2.0 * beta * cov_qw + beta * beta * var_w) * inflation(1) / n);
        // Coherent: <a> - gamma (<b> - E b), gamma = cov(a, b) / var(b); its standard error by the delta method
        // along the estimate's direction (the coherent power moves with that component of the residual a - gamma b).
        const Complex cov_ab(moments.covariance(d, 1, 4) + moments.covariance(d, 2, 5),
                             moments.covariance(d, 2, 4) - moments.covariance(d, 1, 5));
        const Complex gamma = controlled && spread > 0 ? cov_ab / spread : Complex(0.0);
        const Complex mean_amplitude = centre + u - gamma * v;
        const double size = std::abs(mean_amplitude);
        out.coherent[d] = size * size;
        if (size > 0) {
            const Complex direction = std::conj(mean_amplitude) / size, turned = gamma * direction;
            const std::array<double, 6> l{0.0, direction.real(), -direction.imag(), 0.0, -turned.real(), turned.imag()};
            out.coherent_stderr[d] = 2.0 * size * std::sqrt(std::max(0.0, bilinear(moments, d, l, l)) * inflation(2) / n);
        }
    }
    return out;
}

}  // namespace

std::size_t profile_samples(const Exact1dOptions& options, double length_um) {
    const OptionNames& names = options.option_names;
    require_positive(length_um, fmt::format("{} (um)", names.length).c_str());
    require_positive(options.lambda_nm, fmt::format("{} (nm)", names.wavelength).c_str());
    const double spacing = options.lambda_nm * 1e-3 / options.points_per_wavelength;
    const double samples = std::ceil(length_um / spacing) + 1;
    if (!(samples <= kMaxExact1dNodes))
        fail("exact-1d: a profile of {} um at {} nm needs {:.3g} samples, more than {:.0e}: {}", length_um,
             options.lambda_nm, samples, kMaxExact1dNodes, exact_1d_remedy(options, length_um));
    return static_cast<std::size_t>(samples);
}

Profile flat_profile(const Exact1dOptions& options, double length_um) {
    const std::size_t n = profile_samples(options, length_um);
    const double spacing = options.lambda_nm * 1e-3 / options.points_per_wavelength;
    Profile profile;
    profile.spacing_um = spacing;
    profile.x0_um = -0.5 * spacing * static_cast<double>(n - 1);
    profile.h_um.assign(n, 0.0);
    return profile;
}

Profile random_profile(const surface::RadialStatistics& statistics, const Exact1dOptions& options, double length_um,
                       std::uint64_t seed) {
    Profile profile = flat_profile(options, length_um);
    profile.h_um = surface::synthesize_profile(statistics, profile.h_um.size(), profile.spacing_um, seed,
                                               surface::ProfileMean::random);
    return profile;
}

StatisticalResult solve_exact_1d_statistics(const surface::RadialStatistics& statistics,
                                            const material::Conductor& conductor, const Exact1dOptions& options,
                                            const StatisticalOptions& st) {
    if (st.realizations < 2)
        fail("{} must be at least 2 (for a standard error), got {}", options.option_names.realizations, st.realizations);
    if (st.more && st.first_round < 2) fail("the first round must be at least 2 realizations, got {}", st.first_round);
    // The first profile is made before any thread starts, so that bad statistics or lengths fail at once.
    const Profile first = random_profile(statistics, options, st.length_um, st.seed);
    // run_parallel_jobs keeps a done flag per realization: bounded before allocating.
    require_memory(static_cast<double>(st.realizations),
                   fmt::format("{} {} (a done flag each)", options.option_names.realizations, st.realizations));
    // Each thread solves one profile at a time: their buffers together, checked before any thread starts (the
    // profiles share the first's length and statistics, so its planned route stands for theirs).
    const std::size_t concurrent = std::min<std::size_t>(
        st.threads > 0 ? static_cast<std::size_t>(st.threads) : std::max(1u, std::thread::hardware_concurrency()),
        st.realizations);
    require_exact_1d_memory(first, conductor, options, concurrent);
    const KirchhoffControl control(statistics, options, first);
    // Realizations are added to the moments in their order (bit-identical results on any number of threads): a
    // finished one waits in `pending` until those before it are in.
    Moments moments(control.mean);
    std::map<std::size_t, std::pair<std::vector<Complex>, std::vector<Complex>>> pending;
    std::size_t next = 0;
    std::mutex mutex;
    std::vector<double> theta;
    const auto add_ready = [&] {
        while (!pending.empty() && pending.begin()->first == next) {
            moments.add(pending.begin()->second.first, pending.begin()->second.second);
            pending.erase(pending.begin());
            ++next;
        }
    };
    const auto summary = [&] {
        StatisticalResult out = estimates(moments, control, theta);
        out.beam_half_width_rad =
            2.0 / (kTwoPi / (options.lambda_nm * 1e-3) * options.beam_width_um * std::cos(options.theta_i_rad));
        return out;
    };
    // With `more`, rounds until it asks for none (or the cap, or an interruption).
    std::size_t begin = 0, wanted = st.more ? std::min(st.first_round, st.realizations) : st.realizations;
    while (true) {
        const std::vector<char> round =
            run_parallel_jobs(wanted - begin, st.threads, "exact-1d realizations", st.progress, [&] {
                return [&](std::size_t i) {
                    const std::size_t r = begin + i;
                    const Profile profile =
                        r == 0 ? first : random_profile(statistics, options, st.length_um, st.seed + r);
                    FarField field = solve_exact_1d(profile, conductor, options);
                    std::vector<Complex> b = control.amplitude(profile);
                    std::lock_guard<std::mutex> lock(mutex);
                    if (theta.empty()) theta = field.theta_o_rad;
                    pending.emplace(r, std::make_pair(std::move(field.amplitude), std::move(b)));
                    add_ready();
                };
            });
        begin = wanted;
        if (!st.more || wanted >= st.realizations || std::find(round.begin(), round.end(), 0) != round.end()) break;
        const std::size_t extra = st.more(summary());
        if (extra == 0) break;
        wanted = std::min(st.realizations, wanted + extra);
    }
    // Realizations after one that never ran (interrupted), in their order.
    for (const auto& entry : pending) moments.add(entry.second.first, entry.second.second);
    return summary();
}

}  // namespace surfscatter::reference
