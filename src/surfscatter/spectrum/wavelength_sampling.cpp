#include "surfscatter/spectrum/wavelength_sampling.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/math/fast_math.hpp"

namespace surfscatter::spectrum {

namespace {
// p(lambda) = a sech^2(a (lambda - c)) / (T1 - T0) with T = tanh(a (lambda_bound - c)); its CDF is
// (tanh(a (lambda - c)) - T0) / (T1 - T0), inverted in closed form below.
constexpr double kA = 0.0072;   // 1/nm
constexpr double kC = 538.0;    // nm
const double kT0 = std::tanh(kA * (kSampledLambdaMin - kC));
const double kT1 = std::tanh(kA * (kSampledLambdaMax - kC));

// The visible density at the wavelength whose tanh(a (lambda - c)) is t: sech^2 = 1 - tanh^2 = (1 - t)(1 + t).
double pdf_at_tanh(double t) { return kA * (1.0 - t) * (1.0 + t) / (kT1 - kT0); }

// lambda = c + atanh(t) / a with atanh(t) = ln((1 + t) / (1 - t)) / 2: one (inline) logarithm.
double lambda_at_tanh(double t) {
    const double lambda = kC + 0.5 / kA * math::fast_log((1.0 + t) / (1.0 - t));
    return std::clamp(lambda, kSampledLambdaMin, kSampledLambdaMax);
}

double tanh_at(double u) { return kT0 + std::clamp(u, 0.0, 1.0) * (kT1 - kT0); }

}  // namespace

double visible_wavelength_pdf(double lambda_nm) {
    if (!(lambda_nm >= kSampledLambdaMin && lambda_nm <= kSampledLambdaMax)) return 0.0;
    return pdf_at_tanh(std::tanh(kA * (lambda_nm - kC)));
}

double sample_visible_wavelength(double u) { return lambda_at_tanh(tanh_at(u)); }

// On every camera ray: the density comes from the same t as the wavelength (no cosh, no second transcendental).
SampledWavelengths SampledWavelengths::sample_visible(double u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        double ui = u + static_cast<double>(i) / kSpectrumSamples;
        if (ui >= 1.0) ui -= 1.0;
        const double t = tanh_at(ui);
        w.lambda[static_cast<std::size_t>(i)] = lambda_at_tanh(t);
        w.pdf[static_cast<std::size_t>(i)] = pdf_at_tanh(t);
    }
    return w;
}

SampledWavelengths SampledWavelengths::sample_uniform(double u) {
    SampledWavelengths w;
    const double range = kSampledLambdaMax - kSampledLambdaMin;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        double ui = u + static_cast<double>(i) / kSpectrumSamples;
        if (ui >= 1.0) ui -= 1.0;
        w.lambda[static_cast<std::size_t>(i)] = kSampledLambdaMin + ui * range;
        w.pdf[static_cast<std::size_t>(i)] = 1.0 / range;
    }
    return w;
}

}  // namespace surfscatter::spectrum
