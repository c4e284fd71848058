#pragma once
// A scattering model tabulated in the RGL measured format (bsdf/rgl_measured.hpp), so that Mitsuba 3's and
// pbrt-v4's `measured` render it: `surfscatter brdf export`, Python `export_rgl`; accuracy in docs/MODELS.md.
//
// The parameterisation is built from the model itself: an NDF from its retro-reflection, D(m) ~ f(m, m) cos^2
// theta_m at the reference wavelength (the microfacet form f(m, m) = F G D / (4 cos^2 theta_m) read backwards; any
// positive D is valid for the format, a D close to the lobe's makes the tabulated remainder smooth), normalised so
// that int D cos = 1; sigma(wi) = int D(m) <wi, m>+ dm by quadrature; each incidence's VNDF slice (the warp of its
// sample square onto half vectors, which readers only invert) is adapted to that incidence's lobe (rgl_export.cpp,
// docs/MODELS.md); the spectral table holds f(wi, wo) cos(theta_o) 4 sigma(wi) / D(m) at the nodes of the sample
// square, each node mapped to its half vector through the VNDF warp exactly as a reader maps it back, with the
// reader's own interpolated D and sigma (jacobian = 1), so a reader reproduces f exactly at the nodes. The coherent
// specular (delta) part of a model is not in the file (eval excludes it): delta_table() gives it for a separate
// smooth component.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "surfscatter/bsdf/bsdf.hpp"
#include "surfscatter/bsdf/rgl_measured.hpp"

namespace surfscatter::bsdf {

// How messages name the export's options: the CLI's, unless a front end passes its own (Python's keywords), as
// every library check that names a caller's argument takes the name from the caller (docs/RELIABILITY.md).
struct RglExportNames {
    std::string theta_i_count = "--theta-i-count", phi_i_count = "--phi-i-count", ndf_resolution = "--ndf-resolution",
                sample_resolution = "--sample-resolution", lambda_step = "--lambda-step";
};

struct RglExportOptions {
    bool rgb = false;              // rgl-rgb: linear sRGB of each node's spectrum as a reflectance under D65
    int theta_i_count = 16;        // incidences, uniform over [0, theta_i_max_deg] (before refinement)
    double theta_i_max_deg = 88;   // beyond, readers use the last slice (the format's rule)
    int phi_i_count = 17;          // anisotropic models: incidence azimuths over [-pi, pi] (pbrt-v4 reads no other)
    int ndf_resolution = 128;      // NDF, sigma and VNDF: theta_m (u) nodes; phi_m nodes for VNDF and anisotropic NDF
    int sample_resolution = 64;    // luminance and spectral tables: nodes per side of the sample square
    double lambda_min_nm = 360, lambda_max_nm = 1000, lambda_step_nm = 3.2;  // spectral files
    double reference_lambda_nm = 550;  // the NDF's wavelength
    int threads = 0;               // 0: all hardware threads
    // > 0: incidences are added (up to 64) between those whose midpoint the file misses by more than this (percent,
    // at the first, reference and last wavelengths; rgl_accuracy's measure); 0: theta_i_count uniform incidences.
    double tolerance_percent = 0;
    // > 0 (a SpecularAsLobe model: its core_rad()): directions this close to the mirror direction are left out of the
    // refinement's and rgl_file_accuracy's comparison (the lobe's core, whose energy the albedo measures).
    double mirror_exclusion_rad = 0;
    RglExportNames names;
};

// The wavelengths a spectral export holds (o.lambda_min_nm to o.lambda_max_nm in o.lambda_step_nm steps).
std::vector<double> rgl_export_wavelengths(const RglExportOptions& o);
// Bytes of the file export_rgl writes with `incidences` theta_i nodes (its tables; the rest is a few kilobytes), so
// that a caller can say how large it will be before the work.
double rgl_export_bytes(const RglExportOptions& o, bool isotropic, std::size_t incidences);

// The finest spectral step of a file (nm): 6,401 wavelengths over 360-1000 nm, far beyond any measured index table.
inline constexpr double kMinRglLambdaStepNm = 0.1;
// The most incidences the refinement adds up to (tolerance_percent > 0).
inline constexpr std::size_t kMaxRglRefinedIncidences = 64;

// Throws Error, one line naming the option (options.names), for a count, resolution or spectral step out of range
// (the step at least kMinRglLambdaStepNm), or tables that would not fit in the memory available now: the tables in
// double (twice the file), the refinement's trial copy of them, and the file read back for the accuracy check, at
// the most incidences the refinement may reach. Called before anything is allocated, by export_rgl and by the front ends before their other work.
void check_rgl_export_options(const RglExportOptions& options, bool isotropic);

// Throws Error on an option out of range (check_rgl_export_options) or a model the material cannot evaluate
// over the wavelengths (its own message).
RglData export_rgl(const Bsdf& model, const RglExportOptions& options, const std::string& description);

// How well a written file, read back (`file`: the reading of Mitsuba 3's and pbrt-v4's `measured`), reproduces the
// model's continuous part: relative error of f where f >= 1 % of the incidence's peak and theta_o <= 80 degrees (a
// reader divides the tabulated f cos(theta_o) by cos(theta_o), magnifying its interpolation error at the horizon, which
// a render multiplies back), at `incidences` random incidences (theta_i uniform over [0, theta_i_max_deg], phi_i
// uniform), each with `directions` outgoing directions uniform over the hemisphere, as many drawn from the model's own
// sampler (where its lobe is), and the specular direction; at `lambda_nm` (spectral files) or as the CIE Y under D65
// of both spectra over 360-830 nm (rgb files, whose table holds colours); directions within `mirror_exclusion_rad` of
// the mirror direction are left out, the 1 % floor then taken of the peak outside them (a SpecularAsLobe model: its
// lobe's core, whose energy the albedo measures). A model whose lobe jumps (Bsdf::jump_radius: two_scale's micro part,
// whose PSD is 0 below the split) is compared apart within kRglJumpBand of the jump circle: linear interpolation
// across a jump misses it by up to the jump's size wherever a cell straddles it, at any resolution (docs/MODELS.md
// "Export to the RGL format"); those directions give jump_worst, not worst or rms.
// Deterministic (fixed seed).
inline constexpr double kRglJumpBand = 0.3;  // relative half-width in q about the jump radius (measured)
struct RglAccuracy {
    double worst = 0;             // the largest relative error found
    double theta_i_deg = 0, phi_i_deg = 0, theta_o_deg = 0, phi_o_deg = 0, lambda_nm = 0;  // where (lambda 0: Y)
    std::size_t compared = 0;     // directions compared (those where f >= 1 % of the peak, theta_o <= 80)
    double rms = 0;               // root mean square of the relative errors compared
    double jump_band = 0;         // kRglJumpBand for a model that jumps, else 0
    double jump_worst = 0;        // the largest relative error within the band (not in worst)
    std::size_t jump_compared = 0;
};
RglAccuracy rgl_accuracy(const Bsdf& model, const RglMeasuredBsdf& file, double theta_i_max_deg,
                         const std::vector<double>& lambda_nm, bool rgb, int incidences = 24, int directions = 256,
                         double mirror_exclusion_rad = 0);

// The file at `path`, as written by export_rgl with options `o`, read back from disk and measured at its lowest,
// reference and highest wavelengths (rgb files: CIE Y); `where` describes the worst direction in words.
RglAccuracy rgl_file_accuracy(const Bsdf& model, const std::filesystem::path& path, const RglExportOptions& o);
std::string rgl_accuracy_where(const RglAccuracy& accuracy);
// Throws Error naming the file, the error, where, and `option` (how the caller spells the tolerance) when the worst
// error exceeds tolerance_percent; `option` and the value in percent are also checked (> 0, finite).
void check_rgl_accuracy(const RglAccuracy& accuracy, double tolerance_percent, const std::string& option,
                        const std::string& path);

// A model with its coherent specular (delta) part spread into a narrow lobe, so that a tabulated file carries the
// whole reflectance (brdf export --specular-lobe): f(wi, wo) + delta_reflectance(wi) K(wo) / cos(theta_o), K a von
// Mises-Fisher kernel about the mirror direction with kappa = 1 / width^2 (width in radians: the lobe's angular
// standard deviation per axis) and unit integral over the sphere, so that the lobe's albedo is the delta's less the
// kernel's tail below the horizon. sample() draws the model's continuous part and, for its delta, the mirror
// direction (what rgl_accuracy probes).
class SpecularAsLobe final : public Bsdf {
public:
    // Throws Error for a width outside (0, 0.2) rad or a model without a delta part (at 550 nm, theta_i 0-89 deg);
    // `name` is how the messages name the width (the CLI's option, Python's keyword).
    SpecularAsLobe(const Bsdf& model, double width_rad, const std::string& name = "--specular-lobe");
    double eval(const Vec3& wi, const Vec3& wo, double lambda_nm) const override;
    std::optional<BsdfSample> sample(const Vec3& wi, double lambda_nm, double u_lobe, Vec2 u) const override;
    double pdf(const Vec3& wi, const Vec3& wo, double lambda_nm) const override { return model_.pdf(wi, wo, lambda_nm); }
    bool isotropic() const override { return model_.isotropic(); }
    std::string name() const override { return model_.name(); }
    // The lobe's core, 8 standard deviations: what the accuracy measure leaves out (RglExportOptions).
    double core_rad() const { return 8 / std::sqrt(kappa_); }

private:
    const Bsdf& model_;
    double kappa_, norm_;
};

// The coherent specular reflectance the file leaves out, delta_reflectance(wi, lambda), on a theta x lambda grid
// (rows theta_deg, columns lambda_nm): what a separate smooth conductor component must carry.
struct DeltaTable {
    std::vector<double> theta_deg, lambda_nm;
    std::vector<double> reflectance;  // theta-major
};
DeltaTable delta_table(const Bsdf& model, const std::vector<double>& theta_deg, const std::vector<double>& lambda_nm);

}  // namespace surfscatter::bsdf
