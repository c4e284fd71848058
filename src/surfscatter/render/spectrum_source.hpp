#pragma once
// Spectra of the scene file: constant values, tabulated "lambda:value" lists, blackbodies and upsampled RGB.
#include <array>
#include <memory>
#include <vector>

#include "surfscatter/spectrum/rgb_to_spectrum.hpp"
#include "surfscatter/spectrum/wavelength_sampling.hpp"

namespace surfscatter::render {

using spectrum::SampledSpectrum;
using spectrum::SampledWavelengths;

class SpectrumSource {
public:
    virtual ~SpectrumSource() = default;
    virtual double eval(double lambda_nm) const = 0;
    // The four wavelengths of a path in one call (one virtual dispatch, not four).
    virtual SampledSpectrum eval(const SampledWavelengths& w) const = 0;
};

// Implements eval(w) as a loop over the four wavelengths of Derived's inline eval(double) (the CRTP keeps that call
// non-virtual, so the loop inlines it).
template <typename Derived>
class SpectrumSourceBase : public SpectrumSource {
public:
    SampledSpectrum eval(const SampledWavelengths& w) const final {
        SampledSpectrum s;
        for (int i = 0; i < spectrum::kSpectrumSamples; ++i)
            s[i] = static_cast<const Derived&>(*this).Derived::eval(w.lambda[static_cast<std::size_t>(i)]);
        return s;
    }
    using SpectrumSource::eval;
};
using SpectrumPtr = std::shared_ptr<const SpectrumSource>;

// Largest value a spectrum of the scene may take (radiance, intensity, reflectance, texel): path weights times it
// stay far inside the double range, and the film's check on its float output (film.hpp) is the only bound left.
inline constexpr double kMaxSpectrumValue = 1e30;

SpectrumPtr make_constant_spectrum(double value);
// Piecewise-linear through (lambda_nm, value) pairs (strictly increasing lambdas), constant beyond the ends.
SpectrumPtr make_tabulated_spectrum(std::vector<double> lambda_nm, std::vector<double> values);
// Planck's law at `temperature_k` (spectrum/blackbody.hpp units) times `scale`.
SpectrumPtr make_blackbody_spectrum(double temperature_k, double scale);
// A reflectance (bounded) from linear sRGB; channels above 1 are allowed and scale the bounded fit of rgb / max.
SpectrumPtr make_rgb_reflectance(const std::array<double, 3>& linear_srgb);
// An emission spectrum from linear sRGB: the upsampled colour times the D65 illuminant, normalised so that
// rgb (1, 1, 1) has luminance Y = 1 (as Mitsuba's spectral variants do for RGB emitters).
SpectrumPtr make_rgb_illuminant(const std::array<double, 3>& linear_srgb);
// The CIE D65 illuminant scaled to luminance Y = 1 in the film's units, at lambda (nm): what Mitsuba multiplies
// emitters' RGB and constant values by in its spectral variants.
double d65_normalised(double lambda_nm);

}  // namespace surfscatter::render
