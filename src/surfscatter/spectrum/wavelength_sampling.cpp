#include "surfscatter/spectrum/wavelength_sampling.hpp"

#include <algorithm>
#include <cmath>

namespace surfscatter::spectrum {

namespace {
// p(lambda) = a sech^2(a (lambda - c)) / (T1 - T0) with T = tanh(a (lambda_bound - c)); its CDF is
// (tanh(a (lambda - c)) - T0) / (T1 - T0), inverted in closed form below.
constexpr double kA = 0.0072;   // 1/nm
constexpr double kC = 538.0;    // nm
const double kT0 = std::tanh(kA * (kSampledLambdaMin - kC));
const double kT1 = std::tanh(kA * (kSampledLambdaMax - kC));
}  // namespace

double SampledSpectrum::max_value() const { return *std::max_element(v.begin(), v.end()); }
double SampledSpectrum::average() const {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / kSpectrumSamples;
}
bool SampledSpectrum::is_black() const {
    return std::all_of(v.begin(), v.end(), [](double x) { return x == 0.0; });
}

double visible_wavelength_pdf(double lambda_nm) {
    if (!(lambda_nm >= kSampledLambdaMin && lambda_nm <= kSampledLambdaMax)) return 0.0;
    const double c = std::cosh(kA * (lambda_nm - kC));
    return kA / ((kT1 - kT0) * c * c);
}

double sample_visible_wavelength(double u) {
    const double lambda = kC + std::atanh(kT0 + std::clamp(u, 0.0, 1.0) * (kT1 - kT0)) / kA;
    return std::clamp(lambda, kSampledLambdaMin, kSampledLambdaMax);
}

SampledWavelengths SampledWavelengths::sample_visible(double u) {
    SampledWavelengths w;
    for (int i = 0; i < kSpectrumSamples; ++i) {
        double ui = u + static_cast<double>(i) / kSpectrumSamples;
        if (ui >= 1.0) ui -= 1.0;
        w.lambda[static_cast<std::size_t>(i)] = sample_visible_wavelength(ui);
        w.pdf[static_cast<std::size_t>(i)] = visible_wavelength_pdf(w.lambda[static_cast<std::size_t>(i)]);
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
