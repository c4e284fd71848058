#pragma once
// Chi-square goodness-of-fit test of a BSDF sampler (pbrt-v4 / Mitsuba 3 style): histogram of sampled directions
// over a (theta_o, phi_o) grid against the expected counts N * integral of pdf() per cell (Gauss-Legendre
// quadrature per cell), the delta lobe as one more cell, cells with low expectation pooled, and the p-value of
// the statistic compared with a significance level already Sidak-corrected by the caller. While sampling it also
// checks that pdf() equals the pdf sample() returns and that the weight equals f cos / pdf. The generic form takes any
// direction sampler (render materials with transmission and several delta lobes use it, tests/render). Two binnings:
// a (theta, phi) grid, and for BSDFs the lobe's own (|zeta|/k, azimuth within the visible wedge) coordinates.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "surfscatter/bsdf/bsdf.hpp"

namespace surfscatter::bsdf::test {

// Regularised upper incomplete gamma Q(a, x) (series / Lentz continued fraction).
inline double gamma_q(double a, double x) {
    if (x <= 0) return 1.0;
    const double gln = std::lgamma(a);
    if (x < a + 1) {
        double sum = 1.0 / a, del = sum, ap = a;
        for (int n = 0; n < 100000; ++n) {
            ap += 1;
            del *= x / ap;
            sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
    }
    double b = x + 1 - a, c = 1e300, d = 1 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2;
        d = an * d + b;
        if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c;
        if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - gln) * h;
}

struct Chi2Result {
    double p_value = 0;
    double statistic = 0;
    int dof = 0;
    double pdf_mismatch = 0;     // max relative |pdf() - sample().pdf|
    double weight_mismatch = 0;  // max relative |weight - f cos / pdf|
    double expected_total = 0;   // integral of pdf over the hemisphere + delta probability (should be <= 1)
    long failed = 0;             // sample() returned nothing
    std::string summary() const {
        return fmt::format("p = {:.3g}, chi2 = {:.1f}, dof = {}, pdf mismatch {:.2g}, weight mismatch {:.2g}, "
                           "expected mass {:.6f}, failed {}",
                           p_value, statistic, dof, pdf_mismatch, weight_mismatch, expected_total, failed);
    }
};

// What the harness tests: a sampler of directions (continuous or from a finite set of delta directions), its
// claimed density, and optionally the f cos / pdf weight recomputed from eval (NaN to skip that check).
struct DirectionSample {
    Vec3 direction;
    double pdf = 0;     // continuous: solid-angle density; delta: the probability of that outcome
    double weight = 0;  // what the sampler reports as f cos / pdf (continuous samples)
    bool delta = false;
};
struct Chi2Subject {
    std::function<std::optional<DirectionSample>(double u_lobe, Vec2 u)> sample;
    std::function<double(const Vec3&)> pdf;         // density of the continuous part
    std::function<double(const Vec3&)> weight;      // f cos / pdf recomputed; may be empty
    std::vector<std::pair<Vec3, double>> deltas;    // delta directions and their probabilities
    bool full_sphere = false;                       // transmission: histogram theta over [0, pi]
};

namespace detail {

// Draws `samples` directions from the subject: continuous ones into observed[cell_of(direction)], delta ones into
// observed[cells + k] for the announced delta k in that direction; checks pdf and weight of every 97th sample. False
// (and an infinite statistic) if a delta direction was not announced.
template <class CellOf>
bool sample_counts(const Chi2Subject& subject, long samples, std::uint64_t seed, int cells,
                   std::vector<double>& observed, CellOf cell_of, Chi2Result& result) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    for (long n = 0; n < samples; ++n) {
        const double ul = uniform(rng);
        const Vec2 u(uniform(rng), uniform(rng));
        const auto s = subject.sample(ul, u);
        if (!s) {
            ++result.failed;
            continue;
        }
        if (s->delta) {
            int best = -1;
            for (std::size_t k = 0; k < subject.deltas.size(); ++k)
                if (dot(s->direction, subject.deltas[k].first) > 1 - 1e-9) best = static_cast<int>(k);
            if (best < 0) {
                result.statistic = HUGE_VAL;  // a delta direction the subject did not announce
                return false;
            }
            observed[static_cast<std::size_t>(cells + best)] += 1;
            continue;
        }
        observed[static_cast<std::size_t>(cell_of(s->direction))] += 1;
        if (n % 97 == 0) {
            const double p = subject.pdf(s->direction);
            result.pdf_mismatch = std::max(result.pdf_mismatch, std::abs(p - s->pdf) / s->pdf);
            if (subject.weight) {
                const double w = subject.weight(s->direction);
                result.weight_mismatch = std::max(result.weight_mismatch, std::abs(w - s->weight) / std::max(w, 1e-300));
            }
        }
    }
    return true;
}

// The deltas' expected counts after the `cells` continuous ones, the expected mass (`continuous` from the cells plus
// the deltas), then cells expected below 5 pooled (pbrt-v4), the chi-square statistic and its p-value.
inline void finish(const Chi2Subject& subject, long samples, int cells, double continuous,
                   const std::vector<double>& observed, std::vector<double>& expected, Chi2Result& result) {
    double total = continuous;
    for (std::size_t k = 0; k < subject.deltas.size(); ++k) {
        expected[static_cast<std::size_t>(cells) + k] = subject.deltas[k].second * double(samples);
        total += subject.deltas[k].second;
    }
    result.expected_total = total;
    double pooled_obs = 0, pooled_exp = 0, chi2 = 0;
    int kept = 0;
    for (std::size_t c = 0; c < observed.size(); ++c) {
        if (expected[c] == 0 && observed[c] > 0) {
            result.statistic = HUGE_VAL;  // a sample where the pdf says none can be
            result.p_value = 0;
            return;
        }
        if (expected[c] < 5) {
            pooled_obs += observed[c];
            pooled_exp += expected[c];
        } else {
            chi2 += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
            ++kept;
        }
    }
    if (pooled_exp > 0) {
        chi2 += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
        ++kept;
    }
    result.statistic = chi2;
    result.dof = kept - 1;
    result.p_value = result.dof > 0 ? gamma_q(0.5 * result.dof, 0.5 * chi2) : 1.0;
}

inline constexpr double kGauss6X[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                       0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
inline constexpr double kGauss6W[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                       0.4679139345726910, 0.3607615730481386, 0.1713244923791704};

}  // namespace detail

// Cells of a (theta, phi) grid.
inline Chi2Result chi2_test(const Chi2Subject& subject, long samples = 1000000, int theta_bins = 60,
                            int phi_bins = 120, std::uint64_t seed = 7) {
    Chi2Result result;
    const int cells = theta_bins * phi_bins;
    std::vector<double> observed(cells + subject.deltas.size(), 0.0), expected(observed.size(), 0.0);
    const double theta_max = subject.full_sphere ? kPi : 0.5 * kPi;
    const double dtheta = theta_max / theta_bins, dphi = kTwoPi / phi_bins;
    const bool announced = detail::sample_counts(subject, samples, seed, cells, observed, [&](const Vec3& d) {
        const double theta = std::acos(std::clamp(d.z, -1.0, 1.0));
        double phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += kTwoPi;
        return std::min(theta_bins - 1, int(theta / dtheta)) * phi_bins + std::min(phi_bins - 1, int(phi / dphi));
    }, result);
    if (!announced) return result;
    // Expected counts: 6x6 Gauss-Legendre per cell of pdf * sin(theta).
    double total = 0;
    for (int ti = 0; ti < theta_bins; ++ti)
        for (int pi = 0; pi < phi_bins; ++pi) {
            double integral = 0;
            for (int a = 0; a < 6; ++a)
                for (int b = 0; b < 6; ++b) {
                    const double theta = (ti + 0.5 + 0.5 * detail::kGauss6X[a]) * dtheta;
                    const double phi = (pi + 0.5 + 0.5 * detail::kGauss6X[b]) * dphi;
                    integral += detail::kGauss6W[a] * detail::kGauss6W[b] * subject.pdf(spherical_direction(theta, phi)) *
                                std::sin(theta);
                }
            integral *= 0.25 * dtheta * dphi;
            expected[static_cast<std::size_t>(ti * phi_bins + pi)] = integral * double(samples);
            total += integral;
        }
    detail::finish(subject, samples, cells, total, observed, expected, result);
    return result;
}

// A BSDF at incidence wi and one wavelength as a chi-square subject (its delta at the mirror direction).
inline Chi2Subject subject_of(const Bsdf& bsdf, const Vec3& wi, double lambda_nm) {
    Chi2Subject subject;
    subject.sample = [&bsdf, wi, lambda_nm](double ul, Vec2 u) -> std::optional<DirectionSample> {
        const auto s = bsdf.sample(wi, lambda_nm, ul, u);
        if (!s) return std::nullopt;
        return DirectionSample{s->wo, s->pdf, s->weight, s->delta};
    };
    subject.pdf = [&bsdf, wi, lambda_nm](const Vec3& wo) { return bsdf.pdf(wi, wo, lambda_nm); };
    subject.weight = [&bsdf, wi, lambda_nm](const Vec3& wo) {
        const double p = bsdf.pdf(wi, wo, lambda_nm);
        return p > 0 ? bsdf.eval(wi, wo, lambda_nm) * wo.z / p : 0.0;
    };
    const double p_delta = bsdf.delta_probability(wi, lambda_nm);
    if (p_delta > 0) subject.deltas.push_back({reflect_about_normal(wi), p_delta});
    return subject;
}

inline Chi2Result chi2_test(const Bsdf& bsdf, const Vec3& wi, double lambda_nm, long samples = 1000000,
                            int theta_bins = 60, int phi_bins = 120, std::uint64_t seed = 7) {
    return chi2_test(subject_of(bsdf, wi, lambda_nm), samples, theta_bins, phi_bins, seed);
}

// Cells in the wave-optical lobe's own coordinates, for lobes with structure far finer than a (theta, phi) grid (a
// two-scale model's macro spike and the hole of its micro lobe at |zeta| < k/N): q = |i_xy + o_xy| = |zeta|/k on
// logarithmic bins (ratio 1.15 from q_min, plus [0, q_min] and the extra edges given, e.g. zeta_c/k) up to 1 + s, and
// t = (phi - phi_i) / phi_max(q) in [-1, 1] on t_bins uniform bins, phi the azimuth of i_xy + o_xy: every cell lies
// inside the visible disc, so no cell is cut by the horizon. Expected counts: 6x6 Gauss-Legendre per cell of
// pdf / cos(theta_o) q^2 phi_max(q) over (ln q, t) (q phi_max over (q, t) in the first bin).
inline Chi2Result chi2_test_wedge(const Bsdf& bsdf, const Vec3& wi, double lambda_nm, long samples,
                                  std::vector<double> extra_edges = {}, double q_min = 1e-4, int t_bins = 16,
                                  std::uint64_t seed = 7) {
    const double s = std::sqrt(std::max(0.0, 1.0 - wi.z * wi.z)), phi_i = s > 0 ? std::atan2(wi.y, wi.x) : 0.0;
    auto phi_max = [&](double q) {
        if (q <= 1.0 - s) return kPi;
        if (q >= 1.0 + s) return 0.0;
        return std::acos(std::clamp((q * q + s * s - 1.0) / (2.0 * q * s), -1.0, 1.0));
    };
    std::vector<double> edges{0.0, 1.0 + s};
    for (double q = q_min; q < 1.0 + s; q *= 1.15) edges.push_back(q);
    if (s > 0) edges.push_back(1.0 - s);
    for (double e : extra_edges) edges.push_back(e);
    std::sort(edges.begin(), edges.end());
    edges.erase(std::remove_if(edges.begin(), edges.end(), [&](double q) { return q < 0 || q > 1.0 + s; }), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end(), [](double a, double b) { return b - a < 1e-12 * b; }), edges.end());
    const int q_bins = static_cast<int>(edges.size()) - 1, cells = q_bins * t_bins;
    const Chi2Subject subject = subject_of(bsdf, wi, lambda_nm);
    Chi2Result result;
    std::vector<double> observed(cells + subject.deltas.size(), 0.0), expected(observed.size(), 0.0);
    const bool announced = detail::sample_counts(subject, samples, seed, cells, observed, [&](const Vec3& wo) {
        const double x = wi.x + wo.x, y = wi.y + wo.y, q = std::sqrt(x * x + y * y);
        const double phi = std::remainder(std::atan2(y, x) - phi_i, kTwoPi);
        const double pm = phi_max(q), t = pm > 0 ? std::clamp(phi / pm, -1.0, 1.0) : 0.0;
        const int qi = std::clamp(int(std::upper_bound(edges.begin(), edges.end(), q) - edges.begin()) - 1, 0, q_bins - 1);
        return qi * t_bins + std::min(t_bins - 1, int((t + 1.0) * 0.5 * t_bins));
    }, result);
    if (!announced) return result;
    // Density over (q, t): pdf(o) (solid angle) / cos(theta_o) * q phi_max(q)  (d^2 o_xy = q dq dphi).
    auto density = [&](double q, double t) {
        const double pm = phi_max(q), phi = phi_i + t * pm;
        const double ox = q * std::cos(phi) - wi.x, oy = q * std::sin(phi) - wi.y, z2 = 1.0 - ox * ox - oy * oy;
        if (!(z2 > 0) || !(pm > 0)) return 0.0;
        const Vec3 wo(ox, oy, std::sqrt(z2));
        return bsdf.pdf(wi, wo, lambda_nm) / wo.z * q * pm;
    };
    double total = 0;
    for (int qi = 0; qi < q_bins; ++qi)
        for (int ti = 0; ti < t_bins; ++ti) {
            const double t0 = -1.0 + 2.0 * ti / t_bins, dt = 2.0 / t_bins;
            double integral = 0;
            for (int a = 0; a < 6; ++a)
                for (int b = 0; b < 6; ++b) {
                    const double t = t0 + 0.5 * dt * (1.0 + detail::kGauss6X[b]);
                    double q, jacobian;
                    if (qi == 0) {  // [0, q_min]: linear in q
                        q = 0.5 * edges[1] * (1.0 + detail::kGauss6X[a]);
                        jacobian = 0.5 * edges[1];
                    } else {        // ln q
                        const double y0 = std::log(edges[qi]), dy = std::log(edges[qi + 1]) - y0;
                        q = std::exp(y0 + 0.5 * dy * (1.0 + detail::kGauss6X[a]));
                        jacobian = 0.5 * dy * q;
                    }
                    integral += detail::kGauss6W[a] * detail::kGauss6W[b] * jacobian * 0.5 * dt * density(q, t);
                }
            expected[static_cast<std::size_t>(qi * t_bins + ti)] = integral * double(samples);
            total += integral;
        }
    detail::finish(subject, samples, cells, total, observed, expected, result);
    return result;
}

// Per-test significance for `tests` tests at overall level `alpha` (Sidak).
inline double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

}  // namespace surfscatter::bsdf::test
