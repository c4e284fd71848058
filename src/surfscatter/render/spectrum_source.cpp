#include "surfscatter/render/spectrum_source.hpp"

#include <algorithm>
#include <cmath>

#include "surfscatter/core/error.hpp"
#include "surfscatter/spectrum/blackbody.hpp"
#include "surfscatter/spectrum/cie.hpp"

namespace surfscatter::render {

namespace {

class Constant final : public SpectrumSourceBase<Constant> {
public:
    explicit Constant(double v) : value_(v) {}
    double eval(double) const override { return value_; }
    using SpectrumSourceBase::eval;

private:
    double value_;
};

class Tabulated final : public SpectrumSourceBase<Tabulated> {
public:
    Tabulated(std::vector<double> l, std::vector<double> v) : lambda_(std::move(l)), value_(std::move(v)) {}
    double eval(double lambda) const override {
        if (lambda <= lambda_.front()) return value_.front();
        if (lambda >= lambda_.back()) return value_.back();
        const auto it = std::upper_bound(lambda_.begin(), lambda_.end(), lambda);
        const std::size_t i = static_cast<std::size_t>(it - lambda_.begin()) - 1;
        const double t = (lambda - lambda_[i]) / (lambda_[i + 1] - lambda_[i]);
        return value_[i] * (1 - t) + value_[i + 1] * t;
    }
    using SpectrumSourceBase::eval;

private:
    std::vector<double> lambda_, value_;
};

class Blackbody final : public SpectrumSourceBase<Blackbody> {
public:
    Blackbody(double t, double s) : planck_(t), scale_(s) {}
    double eval(double lambda) const override { return scale_ * planck_(lambda); }
    using SpectrumSourceBase::eval;

private:
    spectrum::Planck planck_;
    double scale_;
};

class RgbSpectrum final : public SpectrumSourceBase<RgbSpectrum> {
public:
    RgbSpectrum(spectrum::RgbSigmoid s, double scale, double illuminant_normalisation)
        : sigmoid_(s), scale_(scale), illuminant_(illuminant_normalisation) {}
    double eval(double lambda) const override {
        const double base = scale_ * sigmoid_(lambda);
        return illuminant_ > 0 ? base * d65_(lambda) * illuminant_ : base;
    }
    using SpectrumSourceBase::eval;

private:
    spectrum::RgbSigmoid sigmoid_;
    double scale_;
    double illuminant_;  // 0 for reflectances, else 1 / Y(D65) with the film's normalisation
    const spectrum::RegularSpectrum& d65_ = spectrum::cie_illuminant("D65");
};

spectrum::RgbSigmoid fit_scaled(const std::array<double, 3>& rgb, double& scale) {
    for (double v : rgb)
        if (!(v >= 0 && v <= kMaxSpectrumValue))
            fail("RGB values must be between 0 and {:g}, got ({}, {}, {})", kMaxSpectrumValue, rgb[0], rgb[1], rgb[2]);
    // Reflectances up to 1 are fitted as they are; brighter values (emitters, EXR texels) fit rgb / max, times max.
    const double peak = std::max({rgb[0], rgb[1], rgb[2]});
    scale = peak > 1 ? peak : (peak > 0 ? 1.0 : 0.0);
    if (scale == 0) return spectrum::fit_rgb_sigmoid({0, 0, 0});
    return spectrum::fit_rgb_sigmoid({rgb[0] / scale, rgb[1] / scale, rgb[2] / scale});
}

// 1 / (sum D65 ybar / sum ybar) over 360-830 nm at 1 nm: D65 times this has Y = 1 in the film's units.
double d65_normalisation() {
    static const double value = [] {
        double num = 0, den = 0;
        for (double lambda = spectrum::kSampledLambdaMin; lambda <= spectrum::kSampledLambdaMax; lambda += 1.0) {
            const double y = spectrum::cie1931().xyz_bar(lambda).y;
            num += spectrum::cie_illuminant("D65")(lambda) * y;
            den += y;
        }
        return den / num;
    }();
    return value;
}

void require_spectrum_value(double value, const char* what) {
    if (!(value >= 0 && value <= kMaxSpectrumValue))
        fail("{} must be between 0 and {:g}, got {}", what, kMaxSpectrumValue, value);
}

}  // namespace

double d65_normalised(double lambda_nm) {
    static const spectrum::RegularSpectrum& d65 = spectrum::cie_illuminant("D65");
    static const double normalisation = d65_normalisation();
    return d65(lambda_nm) * normalisation;
}

SpectrumPtr make_constant_spectrum(double value) {
    require_spectrum_value(value, "spectrum value");
    return std::make_shared<Constant>(value);
}

SpectrumPtr make_tabulated_spectrum(std::vector<double> lambda_nm, std::vector<double> values) {
    if (lambda_nm.size() < 2 || lambda_nm.size() != values.size()) fail("a spectrum table needs at least two lambda:value pairs");
    for (std::size_t i = 0; i < lambda_nm.size(); ++i) {
        // Checked here for every source of a table (value lists, .spd files): a wavelength is positive.
        if (!(lambda_nm[i] > 0)) fail("spectrum wavelength {} nm is not positive", lambda_nm[i]);
        if (i > 0 && !(lambda_nm[i] > lambda_nm[i - 1])) fail("spectrum wavelengths must increase, got {} after {}", lambda_nm[i], lambda_nm[i - 1]);
        if (!(values[i] >= 0 && values[i] <= kMaxSpectrumValue))
            fail("spectrum value at {} nm must be between 0 and {:g}, got {}", lambda_nm[i], kMaxSpectrumValue, values[i]);
    }
    return std::make_shared<Tabulated>(std::move(lambda_nm), std::move(values));
}

SpectrumPtr make_blackbody_spectrum(double temperature_k, double scale) {
    spectrum::require_blackbody_temperature(temperature_k, "blackbody temperature");
    require_spectrum_value(scale, "blackbody scale");
    // The peak of the scaled radiance over the rendered wavelengths must be a spectrum value too.
    double peak = 0;
    for (double lambda = spectrum::kSampledLambdaMin; lambda <= spectrum::kSampledLambdaMax; lambda += 1.0)
        peak = std::max(peak, spectrum::blackbody_radiance(lambda, temperature_k));
    require_spectrum_value(scale * peak, "blackbody scale x radiance");
    return std::make_shared<Blackbody>(temperature_k, scale);
}

SpectrumPtr make_rgb_reflectance(const std::array<double, 3>& linear_srgb) {
    double scale = 1;
    const auto sigmoid = fit_scaled(linear_srgb, scale);
    return std::make_shared<RgbSpectrum>(sigmoid, scale, 0.0);
}

SpectrumPtr make_rgb_illuminant(const std::array<double, 3>& linear_srgb) {
    double scale = 1;
    const auto sigmoid = fit_scaled(linear_srgb, scale);
    return std::make_shared<RgbSpectrum>(sigmoid, scale, d65_normalisation());
}

}  // namespace surfscatter::render
