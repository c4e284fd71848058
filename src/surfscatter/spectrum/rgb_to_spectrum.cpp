#include "surfscatter/spectrum/rgb_to_spectrum.hpp"

#include <cmath>
#include <vector>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/cie.hpp"
#include "surfscatter/spectrum/color.hpp"

namespace surfscatter::spectrum {

namespace {

constexpr int kSamples = 471;  // 1 nm

double sigmoid_derivative(double x) {
    const double q = 1.0 + x * x;
    return 0.5 / (q * std::sqrt(q));
}

// weights[i] = linear sRGB response to a unit reflectance at wavelength i under D65, so that
// rgb(s) = sum_i s(lambda_i) weights[i]; scaled per channel so that s = 1 gives exactly (1, 1, 1).
struct ResponseTable {
    std::vector<std::array<double, 3>> weights;
    std::vector<double> t;

    ResponseTable() : weights(kSamples), t(kSamples) {
        const RegularSpectrum& d65 = cie_illuminant("D65");
        std::array<double, 3> total{};
        for (int i = 0; i < kSamples; ++i) {
            const double lambda = kSigmoidLambdaMin + i;
            t[static_cast<std::size_t>(i)] = i / kSigmoidLambdaRange;
            const auto bar = cie1931().xyz_bar(lambda);
            const double e = d65(lambda);
            const Vec3 rgb = xyz_to_linear_srgb(bar * e);
            weights[static_cast<std::size_t>(i)] = {rgb.x, rgb.y, rgb.z};
            for (int c = 0; c < 3; ++c) total[static_cast<std::size_t>(c)] += weights[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
        }
        for (auto& w : weights)
            for (int c = 0; c < 3; ++c) w[static_cast<std::size_t>(c)] /= total[static_cast<std::size_t>(c)];
    }
};

const ResponseTable& table() {
    static const ResponseTable instance;
    return instance;
}

std::array<double, 3> response(const std::array<double, 3>& c, std::array<std::array<double, 3>, 3>* jacobian) {
    const ResponseTable& tab = table();
    std::array<double, 3> rgb{};
    if (jacobian) *jacobian = {};
    for (int i = 0; i < kSamples; ++i) {
        const double t = tab.t[static_cast<std::size_t>(i)];
        const double x = (c[0] * t + c[1]) * t + c[2];
        const double s = rgb_sigmoid(x);
        const auto& w = tab.weights[static_cast<std::size_t>(i)];
        for (std::size_t ch = 0; ch < 3; ++ch) rgb[ch] += s * w[ch];
        if (jacobian) {
            const double ds = sigmoid_derivative(x);
            const double basis[3] = {t * t, t, 1.0};
            for (std::size_t ch = 0; ch < 3; ++ch)
                for (std::size_t k = 0; k < 3; ++k) (*jacobian)[ch][k] += ds * basis[k] * w[ch];
        }
    }
    return rgb;
}

// Solves the 3x3 system A x = b by Cramer's rule; false if A is (numerically) singular.
bool solve3(const std::array<std::array<double, 3>, 3>& a, const std::array<double, 3>& b, std::array<double, 3>& x) {
    auto det = [](const std::array<std::array<double, 3>, 3>& m) {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    };
    const double d = det(a);
    if (!(std::abs(d) > 1e-300)) return false;
    for (std::size_t k = 0; k < 3; ++k) {
        auto m = a;
        for (std::size_t r = 0; r < 3; ++r) m[r][k] = b[r];
        x[k] = det(m) / d;
    }
    return true;
}

double norm2(const std::array<double, 3>& v) { return v[0] * v[0] + v[1] * v[1] + v[2] * v[2]; }

// Damped Gauss-Newton (Levenberg-Marquardt on the 3x3 normal equations) from `c` toward `target`.
void gauss_newton(std::array<double, 3>& c, const std::array<double, 3>& target, int iterations) {
    double lambda = 1e-6;
    std::array<std::array<double, 3>, 3> j{};
    std::array<double, 3> r = response(c, &j);
    for (std::size_t k = 0; k < 3; ++k) r[k] -= target[k];
    double error = norm2(r);
    for (int it = 0; it < iterations && error > 1e-24; ++it) {
        std::array<std::array<double, 3>, 3> jtj{};
        std::array<double, 3> jtr{};
        for (std::size_t a = 0; a < 3; ++a) {
            for (std::size_t b = 0; b < 3; ++b)
                for (std::size_t ch = 0; ch < 3; ++ch) jtj[a][b] += j[ch][a] * j[ch][b];
            for (std::size_t ch = 0; ch < 3; ++ch) jtr[a] -= j[ch][a] * r[ch];
        }
        bool improved = false;
        for (int attempt = 0; attempt < 12 && !improved; ++attempt) {
            auto damped = jtj;
            for (std::size_t a = 0; a < 3; ++a) damped[a][a] *= 1.0 + lambda;
            std::array<double, 3> step{};
            if (!solve3(damped, jtr, step)) {
                lambda *= 10;
                continue;
            }
            const std::array<double, 3> trial{c[0] + step[0], c[1] + step[1], c[2] + step[2]};
            std::array<std::array<double, 3>, 3> j_trial{};
            std::array<double, 3> r_trial = response(trial, &j_trial);
            for (std::size_t k = 0; k < 3; ++k) r_trial[k] -= target[k];
            const double e = norm2(r_trial);
            if (e < error) {
                c = trial;
                j = j_trial;
                r = r_trial;
                error = e;
                lambda = std::max(lambda * 0.1, 1e-12);
                improved = true;
            } else {
                lambda *= 10;
            }
        }
        if (!improved) break;
    }
}

}  // namespace

RgbSigmoid fit_rgb_sigmoid(const std::array<double, 3>& rgb) {
    for (double v : rgb)
        if (!(v >= 0.0 && v <= 1.0)) fail("reflectance RGB must lie in [0, 1], got ({}, {}, {})", rgb[0], rgb[1], rgb[2]);
    RgbSigmoid out;
    if (rgb[0] == rgb[1] && rgb[1] == rgb[2]) {
        // A grey is a constant spectrum: invert the sigmoid (0 and 1 are approached within 1e-12).
        const double y = std::clamp(2 * rgb[0] - 1, -1 + 1e-12, 1 - 1e-12);
        out.c = {0, 0, y / std::sqrt(1 - y * y)};
        return out;
    }
    // Continuation from mid grey (c = 0) toward the target keeps each Gauss-Newton solve in its basin.
    const std::array<double, 3> grey{0.5, 0.5, 0.5};
    std::array<double, 3> c{0, 0, 0};
    constexpr int kSteps = 8;
    for (int step = 1; step <= kSteps; ++step) {
        const double f = static_cast<double>(step) / kSteps;
        std::array<double, 3> target{};
        for (std::size_t k = 0; k < 3; ++k) target[k] = grey[k] + f * (rgb[k] - grey[k]);
        gauss_newton(c, target, step == kSteps ? 60 : 15);
    }
    out.c = c;
    return out;
}

std::array<double, 3> reflectance_to_linear_srgb(const RgbSigmoid& spectrum) { return response(spectrum.c, nullptr); }

}  // namespace surfscatter::spectrum
