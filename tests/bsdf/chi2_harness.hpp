#pragma once
// Chi-square goodness-of-fit test of a BSDF sampler (pbrt-v4 / Mitsuba 3 style): histogram of sampled directions
// over a (theta_o, phi_o) grid against the expected counts N * integral of pdf() per cell (Gauss-Legendre
// quadrature per cell), the delta lobe as one more cell, cells with low expectation pooled, and the p-value of
// the statistic compared with a significance level already Sidak-corrected by the caller. While sampling it also
// checks that pdf() equals the pdf sample() returns and that the weight equals f cos / pdf. The generic form takes any
// direction sampler (render materials with transmission and several delta lobes use it, tests/render).
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

inline Chi2Result chi2_test(const Chi2Subject& subject, long samples = 1000000, int theta_bins = 60,
                            int phi_bins = 120, std::uint64_t seed = 7) {
    Chi2Result result;
    const int cells = theta_bins * phi_bins;
    const int discrete = static_cast<int>(subject.deltas.size());
    std::vector<double> observed(cells + discrete, 0.0), expected(cells + discrete, 0.0);
    const double theta_max = subject.full_sphere ? kPi : 0.5 * kPi;
    const double dtheta = theta_max / theta_bins, dphi = kTwoPi / phi_bins;
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
            for (int k = 0; k < discrete; ++k)
                if (dot(s->direction, subject.deltas[static_cast<std::size_t>(k)].first) > 1 - 1e-9) best = k;
            if (best < 0) {
                result.statistic = HUGE_VAL;  // a delta direction the subject did not announce
                return result;
            }
            observed[cells + best] += 1;
            continue;
        }
        const double theta = std::acos(std::clamp(s->direction.z, -1.0, 1.0));
        double phi = std::atan2(s->direction.y, s->direction.x);
        if (phi < 0) phi += kTwoPi;
        const int ti = std::min(theta_bins - 1, int(theta / dtheta));
        const int pi = std::min(phi_bins - 1, int(phi / dphi));
        observed[ti * phi_bins + pi] += 1;
        if (n % 97 == 0) {
            const double p = subject.pdf(s->direction);
            result.pdf_mismatch = std::max(result.pdf_mismatch, std::abs(p - s->pdf) / s->pdf);
            if (subject.weight) {
                const double w = subject.weight(s->direction);
                result.weight_mismatch = std::max(result.weight_mismatch, std::abs(w - s->weight) / std::max(w, 1e-300));
            }
        }
    }
    // Expected counts: 6x6 Gauss-Legendre per cell of pdf * sin(theta).
    static const double x6[6] = {-0.9324695142031521, -0.6612093864662645, -0.2386191860831969,
                                 0.2386191860831969,  0.6612093864662645,  0.9324695142031521};
    static const double w6[6] = {0.1713244923791704, 0.3607615730481386, 0.4679139345726910,
                                 0.4679139345726910, 0.3607615730481386, 0.1713244923791704};
    double total = 0;
    for (int ti = 0; ti < theta_bins; ++ti)
        for (int pi = 0; pi < phi_bins; ++pi) {
            double integral = 0;
            for (int a = 0; a < 6; ++a)
                for (int b = 0; b < 6; ++b) {
                    const double theta = (ti + 0.5 + 0.5 * x6[a]) * dtheta;
                    const double phi = (pi + 0.5 + 0.5 * x6[b]) * dphi;
                    integral += w6[a] * w6[b] * subject.pdf(spherical_direction(theta, phi)) * std::sin(theta);
                }
            integral *= 0.25 * dtheta * dphi;
            expected[ti * phi_bins + pi] = integral * double(samples);
            total += integral;
        }
    for (int k = 0; k < discrete; ++k) {
        expected[cells + k] = subject.deltas[static_cast<std::size_t>(k)].second * double(samples);
        total += subject.deltas[static_cast<std::size_t>(k)].second;
    }
    result.expected_total = total;
    // Pool low-expectation cells (pbrt-v4: minimum expected frequency 5).
    double pooled_obs = 0, pooled_exp = 0, chi2 = 0;
    int kept = 0;
    for (int c = 0; c < cells + discrete; ++c) {
        if (expected[c] == 0 && observed[c] > 0) {
            result.statistic = HUGE_VAL;  // a sample where the pdf says none can be
            result.p_value = 0;
            return result;
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
    return result;
}

inline Chi2Result chi2_test(const Bsdf& bsdf, const Vec3& wi, double lambda_nm, long samples = 1000000,
                            int theta_bins = 60, int phi_bins = 120, std::uint64_t seed = 7) {
    Chi2Subject subject;
    subject.sample = [&](double ul, Vec2 u) -> std::optional<DirectionSample> {
        const auto s = bsdf.sample(wi, lambda_nm, ul, u);
        if (!s) return std::nullopt;
        return DirectionSample{s->wo, s->pdf, s->weight, s->delta};
    };
    subject.pdf = [&](const Vec3& wo) { return bsdf.pdf(wi, wo, lambda_nm); };
    subject.weight = [&](const Vec3& wo) {
        const double p = bsdf.pdf(wi, wo, lambda_nm);
        return p > 0 ? bsdf.eval(wi, wo, lambda_nm) * wo.z / p : 0.0;
    };
    const double p_delta = bsdf.delta_probability(wi, lambda_nm);
    if (p_delta > 0) subject.deltas.push_back({reflect_about_normal(wi), p_delta});
    return chi2_test(subject, samples, theta_bins, phi_bins, seed);
}

// Per-test significance for `tests` tests at overall level `alpha` (Sidak).
inline double sidak(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

}  // namespace surfscatter::bsdf::test
