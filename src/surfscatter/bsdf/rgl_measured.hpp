#pragma once
// Measured BSDFs in the RGL format of Dupuy & Jakob, "An Adaptive Parameterization for Efficient Material
// Acquisition and Rendering" (ACM TOG 37(6), 2018): the fields of such a file (a Mitsuba tensor_file,
// io/tensor_file.hpp), and `measured`, the BSDF they define, evaluated, sampled and given a density as the format
// prescribes (the reading of Mitsuba 3's and pbrt-v4's `measured`; docs/RENDERER.md).
//
// Parameterisation: an incidence wi (the "table direction", the first argument of eval/sample/pdf, Mitsuba's si.wi)
// at (theta_i, phi_i); half vector m at u_m = (sqrt(2 theta_m / pi), (phi_m [- phi_i if isotropic] + pi) / 2 pi);
// the VNDF table of wi warps uniform variates onto u_m (math/marginal_2d.hpp) and its inverse maps u_m to the
// "sample" point at which the luminance and spectral tables are read. f(wi, wo) cos(theta_o) = spectrum(sample) *
// [jacobian: ndf(u_m) / (4 sigma(u_wi))]. Isotropic files have one phi_i (or two); otherwise phi_i spans 2 pi / r
// and wi is folded into it by the r-fold symmetry (r = 2 or 4, as Mitsuba 3).
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/io/tensor_file.hpp"
#include "surfscatter/math/marginal_2d.hpp"

namespace surfscatter::bsdf {

// The fields of an RGL file, as doubles. Shapes: ndf and sigma (rows = phi, cols = theta; u coordinates),
// vndf (phi_i, theta_i, vndf_rows, vndf_cols), luminance (phi_i, theta_i, rows, cols), spectra (phi_i, theta_i,
// channels, rows, cols) where channels = wavelengths.size() (spectral files) or 3 (rgb files: linear sRGB).
struct RglData {
    std::string description;
    std::uint32_t version[2] = {1, 0};
    std::vector<double> theta_i, phi_i;  // radians, increasing
    bool jacobian = true;
    std::size_t ndf_rows = 0, ndf_cols = 0, sigma_rows = 0, sigma_cols = 0;
    std::vector<double> ndf, sigma;
    std::size_t vndf_rows = 0, vndf_cols = 0;
    std::vector<double> vndf;
    std::size_t rows = 0, cols = 0;  // of luminance and spectra
    std::vector<double> luminance;
    bool rgb = false;
    std::vector<double> wavelengths;  // nm (spectral)
    std::vector<double> spectra;      // or rgb
    std::string valid;                // the `valid` bit mask, kept as it is (no reader uses it)

    std::size_t channels() const { return rgb ? 3 : wavelengths.size(); }
    bool isotropic() const { return phi_i.size() <= 2; }
};

// Checks every field's presence, dtype and shape against the others (as Mitsuba 3's reader does); `origin` names the
// file in messages. Values must be finite, tables non-negative.
RglData rgl_from_tensor(const io::TensorFile& file, const std::string& origin);
io::TensorFile rgl_to_tensor(const RglData& data);
RglData read_rgl(const std::filesystem::path& path);
void write_rgl(const std::filesystem::path& path, const RglData& data);

// The u coordinates of the format: theta -> sqrt(2 theta / pi), phi -> (phi + pi) / 2 pi, and back.
double rgl_theta_to_u(double theta);
double rgl_u_to_theta(double u);
double rgl_phi_to_u(double phi);
double rgl_u_to_phi(double u);
// Polar angle of a unit vector, accurate near the pole (2 asin(|w - z| / 2)).
double rgl_elevation(const Vec3& w);

class RglMeasuredBsdf final : public Bsdf {
public:
    // RGB files are turned into spectra once, node by node (spectrum/rgb_to_spectrum.hpp, scaled by the largest
    // channel for values above 1) on 5 nm steps over 360-830 nm, so that the colour of every interpolated value is the
    // interpolation of the file's colours.
    explicit RglMeasuredBsdf(const RglData& data, std::string name = "measured");

    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    bool isotropic() const override { return isotropic_; }
    std::string name() const override { return name_; }

    // The spectral table's value at the sample point and incidence (what eval multiplies by the Jacobian factor).
    double table_value(Vec2 sample, double phi_i, double theta_i, double lambda_nm) const;
    const std::vector<double>& wavelengths() const { return wavelengths_; }

private:
    struct Frame {  // wi folded by the symmetry, and the signs that undo it
        Vec3 wi;
        double sx = 1, sy = 1;
    };
    Frame fold(const Vec3& wi) const;
    // A pair of directions (z > 0) as the tables index them: the folded incidence, the half vector, its warped
    // coordinates u_m and the incidence parameters (phi_i, theta_i).
    struct Lookup {
        Vec3 wi, m;
        Vec2 u_m;
        double params[2];
    };
    Lookup lookup(const Vec3& wi, const Vec3& wo) const;
    void check_lambda(double lambda_nm) const;

    std::string name_;
    bool isotropic_ = true, jacobian_ = true;
    int reduction_ = 1;
    std::vector<double> wavelengths_;
    Marginal2D ndf_, sigma_, vndf_, luminance_, spectra_;
};

}  // namespace surfscatter::bsdf
