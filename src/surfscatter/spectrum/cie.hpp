#pragma once
// CIE colorimetric data read from the Debian package colord-data (CGATS text files): the CIE 1931 2-degree
// colour-matching functions (5 nm, 360-830 nm) and the CIE standard illuminants (relative SPDs). Both are
// interpolated linearly in wavelength and are 0 outside their tables. Spectra are integrated to XYZ on a 1 nm grid.
#include <algorithm>
#include <string>
#include <vector>

#include "surfscatter/math/vec.hpp"

namespace surfscatter::spectrum {

inline constexpr const char* kCie1931CmfPath = "/usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf";
inline constexpr const char* kCieIlluminantDirectory = "/usr/share/colord/illuminant";

// Spectral sets of one CGATS file with a regular wavelength grid given by SPECTRAL_START_NM and SPECTRAL_END_NM,
// one SPEC_* field per band (SPECTRAL_BANDS, if present, must equal their number). Throws Error naming the file (and line) if it is missing or
// malformed.
struct CgatsSpectra {
    double start_nm = 0;
    double step_nm = 0;
    std::vector<std::vector<double>> sets;  // each has one value per band
};
CgatsSpectra read_cgats_spectra(const std::string& path);

// A curve on a regular wavelength grid, linear interpolation inside, 0 outside.
class RegularSpectrum {
public:
    RegularSpectrum(double start_nm, double step_nm, std::vector<double> values);
    double operator()(double lambda_nm) const {
        std::size_t i;
        double f;
        return locate(lambda_nm, i, f) ? values_[i] + f * (values_[i + 1] - values_[i]) : 0.0;
    }
    // The interval [i, i + 1] holding lambda and the position f in [0, 1] within it; false outside the grid (and on
    // NaN). The last node is the interval before it at f = 1.
    bool locate(double lambda_nm, std::size_t& i, double& f) const {
        const double t = (lambda_nm - start_nm_) * inv_step_;
        const double last = static_cast<double>(values_.size() - 1);
        if (!(t >= 0.0 && t <= last)) return false;
        i = std::min(static_cast<std::size_t>(t), values_.size() - 2);
        f = t - static_cast<double>(i);
        return true;
    }
    double min_wavelength_nm() const { return start_nm_; }
    double max_wavelength_nm() const { return start_nm_ + step_nm_ * static_cast<double>(values_.size() - 1); }
    double step_nm() const { return step_nm_; }
    const std::vector<double>& values() const { return values_; }

private:
    double start_nm_, step_nm_, inv_step_;
    std::vector<double> values_;
};

// Colour-matching functions xbar, ybar, zbar. xyz_bar() is O(1) (one index for the three curves, which share the
// grid, and three lerps): cheap enough per path.
class CieTable {
public:
    static CieTable load(const std::string& cmf_path);
    Vec3 xyz_bar(double lambda_nm) const {
        std::size_t i;
        double f;
        if (!x_.locate(lambda_nm, i, f)) return {0, 0, 0};
        const auto lerp = [&](const RegularSpectrum& s) { return s.values()[i] + f * (s.values()[i + 1] - s.values()[i]); };
        return {lerp(x_), lerp(y_), lerp(z_)};
    }
    double min_wavelength_nm() const { return x_.min_wavelength_nm(); }
    double max_wavelength_nm() const { return x_.max_wavelength_nm(); }

private:
    CieTable(RegularSpectrum x, RegularSpectrum y, RegularSpectrum z);
    RegularSpectrum x_, y_, z_;
};

// The CIE 1931 2-degree observer from kCie1931CmfPath, loaded on first use (thread-safe).
const CieTable& cie1931();

// A CIE standard illuminant by name ("D65", "D50", "A", "F2", ...; case-insensitive), i.e. the file
// CIE-<name>.sp of kCieIlluminantDirectory, loaded once. Relative SPD (only ratios matter). Throws Error naming the
// value and the known names if there is no such file.
const RegularSpectrum& cie_illuminant(const std::string& name);
std::vector<std::string> cie_illuminant_names();

// XYZ of a spectrum (any callable double(double lambda_nm)): the sum of s(lambda) xyz_bar(lambda) dlambda over the
// CMF range on a grid of step_nm (1 nm by default; a Riemann sum equals the trapezoid rule here since the CMFs
// vanish at both ends to 1e-4 of their peak).
template <typename Spectrum>
Vec3 spectrum_to_xyz(const Spectrum& spectrum, double step_nm = 1.0) {
    const CieTable& cie = cie1931();
    Vec3 xyz;
    const int n = static_cast<int>((cie.max_wavelength_nm() - cie.min_wavelength_nm()) / step_nm + 0.5);
    for (int i = 0; i <= n; ++i) {
        const double lambda = cie.min_wavelength_nm() + step_nm * i;
        xyz += cie.xyz_bar(lambda) * (spectrum(lambda) * step_nm);
    }
    return xyz;
}

// XYZ of a surface of spectral reflectance `reflectance` lit by `illuminant`, normalised so that the perfect white
// reflector (reflectance 1) has Y = 1.
template <typename Reflectance, typename Illuminant>
Vec3 reflectance_to_xyz(const Reflectance& reflectance, const Illuminant& illuminant, double step_nm = 1.0) {
    const Vec3 reflected = spectrum_to_xyz([&](double l) { return reflectance(l) * illuminant(l); }, step_nm);
    const double white_y = spectrum_to_xyz(illuminant, step_nm).y;
    return reflected / white_y;
}

}  // namespace surfscatter::spectrum
