#include "surfscatter/bsdf/factory.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "surfscatter/bsdf/anisotropic_ghs.hpp"
#include "surfscatter/bsdf/ggx.hpp"
#include "surfscatter/bsdf/map_ghs.hpp"
#include "surfscatter/bsdf/microfacet.hpp"
#include "surfscatter/bsdf/ghs.hpp"
#include "surfscatter/bsdf/ghs_ssa.hpp"
#include "surfscatter/bsdf/scatter_core.hpp"
#include "surfscatter/bsdf/two_scale.hpp"
#include "surfscatter/core/error.hpp"
#include "surfscatter/heightmap/io.hpp"
#include "surfscatter/surface/height_map_slope.hpp"
#include "surfscatter/surface/elliptical_slopes.hpp"
#include "surfscatter/surface/elliptical_statistics.hpp"
#include "surfscatter/surface/kc_fit.hpp"
#include "surfscatter/surface/map_statistics.hpp"
#include "surfscatter/surface/psd_split.hpp"
#include "surfscatter/surface/refit.hpp"

namespace surfscatter::bsdf {

namespace {

constexpr int kRefitOrders = 13;  // orders fitted for the L m^-x power law (THEORY 2.4)

bool needs_surface(const ModelOptions& o) {
    return o.model != ModelKind::ggx || o.alpha_from != AlphaFrom::none;
}

void validate_lay(const SurfaceOptions& s) {
    if (s.corr_length_v != 0) surface::require_surface_length(s.corr_length_v, "corr_length_v");
    if (!std::isfinite(s.lay_angle)) fail("lay_angle must be finite (degrees), got {}", s.lay_angle);
}

void validate_surface(const SurfaceOptions& s) {
    if (s.psd_fit == PsdFit::elliptical && s.psd != PsdKind::file)
        fail("psd_fit elliptical needs psd file (the elliptical KC fitted to a height map), got psd {}", to_string(s.psd));
    switch (s.psd) {
        case PsdKind::kc:
            surface::require_surface_length(s.sigma, "sigma");
            surface::require_surface_length(s.corr_length, "corr_length");
            surface::require_kc_gamma(s.gamma, "gamma");
            validate_lay(s);
            break;
        case PsdKind::gaussian:
            surface::require_surface_length(s.sigma, "sigma");
            surface::require_surface_length(s.corr_length, "corr_length");
            validate_lay(s);
            break;
        case PsdKind::measured:
            if (s.measured_psd || s.measured_profile) break;
            [[fallthrough]];
        case PsdKind::file:
            if (s.surface_file.empty()) fail("surface_file is empty: give a height map file for psd {}", to_string(s.psd));
            break;
    }
}

// Standard error of a measured PSD's sigma above which the models warn.
constexpr double kWarnMeasuredSigmaError = 0.10;

// The surface of a model's options: its height map (psd file or measured; read by load_height_map unless the caller
// shares one already read) and the statistics, built once however many derived quantities (KC fit, PSD, slope) the
// model needs.
class SurfaceSource {
public:
    explicit SurfaceSource(SurfaceOptions s) : options_(std::move(s)) { load_height_map(options_); }

    // The prepared map (its form removed: statistics take it with Form::none), or null.
    const heightmap::HeightMap* map() const { return options_.prepared ? &options_.prepared->map : nullptr; }
    // Mean square slope of the map's waviness (what its L-filter removed), 0 without one.
    double waviness_slope2() const {
        if (!options_.prepared || !options_.prepared->waviness) return 0.0;
        const double s = surface::rms_slope(*options_.prepared->waviness, heightmap::Form::none);
        return s * s;
    }
    const SurfaceOptions& options() const { return options_; }

    // KC parameters: given, or fitted to the height map after form removal (kc_fit.hpp); with psd_fit elliptical the
    // elliptical fit's sigma, LU and gamma (its LV and lay angle: elliptical()).
    surface::KCorrelation kc() {
        if (options_.psd == PsdKind::kc)
            return surface::KCorrelation(options_.sigma, options_.corr_length, options_.gamma);
        if (options_.psd == PsdKind::file && options_.psd_fit == PsdFit::elliptical) {
            const surface::EllipticalKcFit& e = map_fit().elliptical;
            surface::require_resolved(e);
            return surface::KCorrelation(e.sigma_h_um, e.corr_length_u_um, e.gamma);
        }
        if (options_.psd == PsdKind::file) {
            const surface::KcFit& fit = map_fit().kc;
            surface::require_resolved(fit);
            const double ratio = map_fit().fit_lattice_rms_um / map_fit().map_lattice_rms_um;
            if (ratio > surface::kLatticeRmsRefusal || ratio < 1.0 / surface::kLatticeRmsRefusal)
                fail("psd file{}: {}", of_file(), surface::lattice_rms_check(map_fit()));
            return surface::KCorrelation(fit.sigma_h_um, fit.corr_length_um, fit.gamma);
        }
        fail("this option needs a K-correlation surface (psd kc, or file for the KC fitted to a height map), got psd {}",
             to_string(options_.psd));
    }

    std::shared_ptr<const surface::RadialStatistics> statistics(std::vector<std::string>* notes) {
        if (statistics_) return statistics_;
        switch (options_.psd) {
            case PsdKind::gaussian:
                statistics_ = std::make_shared<surface::GaussianAcv>(options_.sigma, options_.corr_length);
                break;
            case PsdKind::measured: {
                if (options_.measured_profile) {  // a profile as an isotropic surface
                    const auto& profile = options_.measured_profile;
                    check_measured_uncertainty(*profile, notes);
                    if (notes) notes->push_back(surface::measured_profile_note(*profile, options_.surface_file));
                    measured_ = profile;
                    statistics_ = profile;
                    break;
                }
                // Estimated already (Python's measured_statistics), or from the map.
                auto measured = options_.measured_psd
                                    ? options_.measured_psd
                                    : std::make_shared<const surface::MapStatistics>(*map(), heightmap::Form::none);
                check_measured_uncertainty(*measured, notes);
                if (notes) notes->push_back(measured_note(*measured));
                measured_ = measured;
                statistics_ = std::move(measured);
                break;
            }
            default:
                statistics_ = std::make_shared<surface::KCorrelation>(kc());
                if (options_.psd == PsdKind::file && notes)
                    if (const std::string lattice = surface::lattice_rms_check(map_fit()); !lattice.empty())
                        notes->push_back(fmt::format("warning: psd file{}: {}", of_file(), lattice));
                break;
        }
        return statistics_;
    }

    // The elliptical statistics (model_options.hpp: corr_length_v, lay_angle), or null for an isotropic surface
    // (corr_length_v 0 or equal to corr_length): every isotropic result stays exactly what it was.
    std::shared_ptr<const surface::EllipticalStatistics> elliptical(std::vector<std::string>* notes) {
        if (options_.psd == PsdKind::file && options_.psd_fit == PsdFit::elliptical) {
            const auto radial = statistics(notes);  // refuses an unresolved fit
            const surface::EllipticalKcFit& e = map_fit().elliptical;
            if (notes) notes->push_back(elliptical_fit_note(e));
            return std::make_shared<const surface::EllipticalStatistics>(radial, e.corr_length_v_um,
                                                                         e.lay_angle_deg * kDegree);
        }
        const double lv = options_.corr_length_v;
        if (lv == 0 || lv == options_.corr_length) return nullptr;
        return std::make_shared<const surface::EllipticalStatistics>(statistics(notes), lv,
                                                                     options_.lay_angle * kDegree);
    }

private:
    // " of <file>" for the notes, or nothing for statistics given without a file.
    std::string of_file() const { return options_.surface_file.empty() ? "" : " of " + options_.surface_file; }

    // Both KC fits of the map (fit_surface), computed once.
    const surface::SurfaceFit& map_fit() {
        if (!map_fit_) {
            surface::KcFitOptions fit_options;
            fit_options.form = heightmap::Form::none;
            map_fit_ = std::make_unique<const surface::SurfaceFit>(surface::fit_surface(*map(), fit_options));
        }
        return *map_fit_;
    }

    // What the models use of psd_fit elliptical, with its standard errors and whether the data tell it from an
    // isotropic surface (elliptical_fit.hpp); its misfit when the elliptical KC describes the 2-D PSD poorly.
    std::string elliptical_fit_note(const surface::EllipticalKcFit& e) const {
        std::string note = fmt::format(
            "psd_fit elliptical{}: KC sigma {:.4g} +- {:.2g} um, corr_length (LU) {:.4g} +- {:.2g} um, corr_length_v "
            "(LV) {:.4g} +- {:.2g} um, lay_angle {:.4g} +- {:.2g} deg, gamma {:.4g} +- {:.2g} (LV / LU {:.3g} +- "
            "{:.2g}; {} cells, {} window); ",
            of_file(), e.sigma_h_um, e.sigma_h_error_um, e.corr_length_u_um, e.corr_length_u_error_um,
            e.corr_length_v_um, e.corr_length_v_error_um, e.lay_angle_deg, e.lay_angle_error_deg, e.gamma,
            e.gamma_error, e.axis_ratio(), e.axis_ratio_error, e.cells,
            e.window == surface::Window::rectangular ? "rectangular" : "Hann");
        if (e.anisotropic())
            note += fmt::format("the anisotropy is significant (chi-square {:.3g} > {:.3g}, false-alarm probability "
                                "1e-3 for an isotropic surface)",
                                e.anisotropy_chi2, surface::kAnisotropyChi2);
        else
            note += fmt::format("warning: the anisotropy is not significant (chi-square {:.3g} <= {:.3g}): the data do "
                                "not tell this surface from an isotropic one, and the lay angle is undetermined; "
                                "psd_fit isotropic describes the map as well",
                                e.anisotropy_chi2, surface::kAnisotropyChi2);
        if (e.log_residual_rms > surface::kPoorFitFactor * e.statistical_floor)
            note += fmt::format("; warning: the elliptical KC fits this 2-D PSD poorly (log residual rms {:.3g}, {:.1f} "
                                "times its statistical floor)",
                                e.log_residual_rms, e.log_residual_rms / e.statistical_floor);
        return note;
    }

    // A map whose variance sits in its few longest periods gives a sigma (and so g) no better than those few samples:
    // a warning above kWarnMeasuredSigmaError (surface::MapStatistics::sigma_relative_error()). Never refused: the
    // default L-filter (heightmap/prepare.hpp) leaves such periods to the waviness, and a user who keeps them is told.
    void check_measured_uncertainty(const surface::MeasuredStatistics& s, std::vector<std::string>* notes) const {
        const double error = s.sigma_relative_error();
        if (error > kWarnMeasuredSigmaError && notes)
            notes->push_back(fmt::format(
                "warning: the measured PSD{} rests on a few long periods: the standard error of its sigma is {:.2g} % "
                "(rings 1-3, {:.3g} .. {:.3g} um periods, hold {:.2g} % of the variance), and g and every lobe are as "
                "uncertain; an L-filter (--lambda-c) leaves such periods to the waviness",
                of_file(), 100.0 * error, kTwoPi / (3 * s.ring_width()), kTwoPi / s.first_ring(),
                100.0 * s.radial_cdf(3.5 * s.ring_width())));
        check_stationarity(s, notes);
    }

    // The Hann window weighs the map's centre: the periodogram is scaled to the whole map's variance (map_statistics.hpp
    // window_scale()). Where the factor departs from 1 by more than the long periods' scatter explains (twice sigma's
    // standard error, and at least 10 %), the roughness varies across the map (or form is left at its edges): the
    // spectrum's shape is the centre's, its level the whole map's, and the note says so.
    void check_stationarity(const surface::MeasuredStatistics& s, std::vector<std::string>* notes) const {
        const double ratio = std::sqrt(1.0 / s.window_scale());  // the centre's rms over the whole map's
        if (!notes || std::abs(ratio - 1.0) <= std::max(0.1, 2.0 * s.sigma_relative_error())) return;
        notes->push_back(fmt::format(
            "warning: the Hann window weighs the centre of the map{}, whose rms is {:.0f} % {} the whole map's ({:.3g} "
            "um), more than the long periods' scatter ({:.2g} %) explains: the map is not stationary (or form is left "
            "at its edges: try a higher --form or --lambda-c); the spectrum's shape follows its centre, its level the "
            "whole map (window correction)",
            of_file(), 100.0 * std::abs(ratio - 1.0), ratio < 1 ? "below" : "above", s.map_rms(),
            100.0 * s.sigma_relative_error()));
    }

    // What a measured PSD rests on (map_statistics.hpp): the band, the variance the model carries against the map's
    // own, the estimate's uncertainty at the lowest rings, and where lobes start to draw on periods longer than a
    // third of the map: |zeta| < 3 dzeta, i.e. within asin(3 dzeta / k) of the specular direction at normal incidence.
    std::string measured_note(const surface::MapStatistics& s) const {
        const double dz = s.ring_width();
        return fmt::format(
            "measured PSD{} ({}{}): band zeta {:.3g} .. {:.3g} rad/um (lateral periods {:.3g} .. {:.3g} um), rolled "
            "off as zeta^-200 beyond ({:.2g} % of sigma^2 there); model sigma {:.6g} um against the map's rms {:.6g} "
            "um ({:.2g} % of sigma^2 below the first ring, continued from the DC bin, itself continued from the lowest ring; standard error of "
            "sigma {:.2g} %); rings 1-3 rest on {:.3g}, {:.3g}, {:.3g} independent samples; lobes draw on periods "
            "longer than a third of the map (> {:.3g} um) where |zeta| < {:.3g} rad/um, within about {:.2g} deg of "
            "the specular direction at 550 nm; lobes reach beyond the band at wavelengths below {:.0f} nm (below "
            "{:.0f} nm at normal incidence)",
            of_file(), s.periodic() ? "periodic map, rectangular window" : "Hann window",
            s.skipped_rings() ? fmt::format(", {} non-positive rings skipped", s.skipped_rings()) : "", s.first_ring(),
            s.nyquist(), kTwoPi / s.nyquist(), kTwoPi / s.first_ring(), 100.0 * s.above_band_fraction(), s.sigma_h(),
            s.map_rms(), 100.0 * s.below_band_fraction(), 100.0 * s.sigma_relative_error(), s.ring_samples(dz),
            s.ring_samples(2 * dz), s.ring_samples(3 * dz), kTwoPi / (3 * dz), 3 * dz,
            std::asin(std::min(1.0, 3 * dz / (kTwoPi / 0.55))) * 180.0 / kPi, 2e3 * kTwoPi / s.nyquist(),
            1e3 * kTwoPi / s.nyquist());
    }

    SurfaceOptions options_;
    std::shared_ptr<const surface::RadialStatistics> statistics_;
    std::unique_ptr<const surface::SurfaceFit> map_fit_;
    std::shared_ptr<const surface::MeasuredStatistics> measured_;

public:
    // psd measured: the map's or profile's statistics (its checks and notes made).
    const surface::MeasuredStatistics& measured(std::vector<std::string>* notes) {
        statistics(notes);
        return *measured_;
    }
};

// The refusal of alpha_from measured / smoothed where the surface's rms slope diverges.
[[noreturn]] void fail_divergent_slope(const ModelOptions& o) {
    const bool kc = o.surface.psd == PsdKind::kc;
    fail("alpha_from {}: the rms slope of {} diverges{}; use alpha_from kc_link (alpha from the correlation length and "
         "the wavelength), alpha_from smoothed with smoothing S > 0 (um, the slope seen at that lateral resolution), a "
         "height map, or alpha_from none with alpha A",
         to_string(o.alpha_from), kc ? fmt::format("a KC surface with gamma = {}", o.surface.gamma) : "this PSD",
         kc ? " (it is finite for gamma > 3 only)" : "");
}

// alpha_from measured / smoothed: `alpha` (the rms slope, or `what` of it) checked against GGX's range.
double checked_slope_alpha(const ModelOptions& o, double smoothing, double alpha, const char* what) {
    if (!(alpha >= kMinMicrofacetAlpha && alpha <= kMaxMicrofacetAlpha))
        fail("alpha_from {} gives {} = {} (the surface's rms slope{}), outside GGX's range {} to {}",
             to_string(o.alpha_from), what, alpha, smoothing > 0 ? fmt::format(" after smoothing {} um", smoothing) : "",
             kMinMicrofacetAlpha, kMaxMicrofacetAlpha);
    return alpha;
}

double slope_smoothing(const ModelOptions& o) { return o.alpha_from == AlphaFrom::smoothed ? o.smoothing : 0.0; }

std::function<double(double)> ggx_alpha(const ModelOptions& o, SurfaceSource& surface, std::vector<std::string>* notes) {
    const auto constant = [](double a) { return std::function<double(double)>([a](double) { return a; }); };
    switch (o.alpha_from) {
        case AlphaFrom::none: return constant(o.alpha);
        case AlphaFrom::measured:
        case AlphaFrom::smoothed: {
            const double smoothing = slope_smoothing(o);
            double alpha = 0;  // alpha_GGX = alpha_Beckmann = rms slope (THEORY 4.2)
            if (const heightmap::HeightMap* map = surface.map()) {  // its own slopes, whether the PSD is fitted or measured
                alpha = smoothing > 0 ? surface::rms_slope_smoothed(*map, smoothing, heightmap::Form::none)
                                      : surface::rms_slope(*map, heightmap::Form::none);
            } else {
                const double no_cutoff = std::numeric_limits<double>::infinity();
                const double slope2 = surface.statistics(notes)->mean_square_slope(smoothing, no_cutoff);
                if (!std::isfinite(slope2)) fail_divergent_slope(o);
                alpha = std::sqrt(slope2);
            }
            return constant(checked_slope_alpha(o, smoothing, alpha, "alpha"));
        }
        case AlphaFrom::kc_link: {
            const double length = surface.kc().correlation_length();
            return [length](double lambda_nm) { return kc_link_alpha(length, lambda_nm); };
        }
    }
    return constant(o.alpha);
}

// ggx_stats on elliptical statistics (docs/MODELS.md, "Anisotropic GGX"). measured / smoothed: per lay axis the
// Beckmann convention of THEORY 4.2, alpha = sqrt(2 <h_axis^2>) (a Beckmann slope density has the per-axis variance
// alpha^2 / 2), so that LV = LU gives alpha_u = alpha_v = sqrt(<|grad h|^2>), the isotropic alpha = rms slope;
// smoothed uses the isotropic Gaussian smoothing's covariance (surface/elliptical_slopes.hpp). kc_link: the
// elliptical KC(3) lobe is the anisotropic GGX of kc_link_alpha(LU) along u and kc_link_alpha(LV) along v (ggx.hpp).
std::unique_ptr<Bsdf> elliptical_ggx(const ModelOptions& o, SurfaceSource& surface,
                                     const surface::EllipticalStatistics& elliptical, material::Conductor material) {
    const double lay = elliptical.lay_angle();
    if (o.alpha_from == AlphaFrom::kc_link) {
        const double lu = elliptical.corr_length_u(), lv = elliptical.corr_length_v();
        surface.kc();  // kc_link needs a KC surface, as for the isotropic one
        return std::make_unique<GgxBsdf>(
            std::move(material), [lu](double lambda_nm) { return kc_link_alpha(lu, lambda_nm); },
            [lv](double lambda_nm) { return kc_link_alpha(lv, lambda_nm); }, lay);
    }
    const double smoothing = slope_smoothing(o);
    // A height map (psd_fit elliptical) gives its own slopes along the fitted lay axes, as the isotropic route does.
    const heightmap::HeightMap* map = surface.map();
    const Vec2 variances =
        !map ? surface::smoothed_slope_variances_lay(elliptical, smoothing)
        : smoothing > 0
            ? surface::slope_variances_lay(surface::gaussian_smooth(*map, smoothing, heightmap::Form::none), lay, heightmap::Form::none)
            : surface::slope_variances_lay(*map, lay, heightmap::Form::none);
    if (!std::isfinite(variances.x) || !std::isfinite(variances.y)) fail_divergent_slope(o);
    const Vec2 alpha(checked_slope_alpha(o, smoothing, std::sqrt(2 * variances.x), "alpha_u"),
                     checked_slope_alpha(o, smoothing, std::sqrt(2 * variances.y), "alpha_v"));
    return std::make_unique<GgxBsdf>(std::move(material), alpha, lay);
}

// The macro NDF's alpha from a low-pass mean-square slope, unclamped (it was floored at 1e-4, which widened the macro
// lobe of smooth, long-correlated surfaces); a low-pass part without slope would be a mirror, not an NDF.
double macro_alpha(const ModelOptions& o, double slope2) {
    const double alpha = std::sqrt(slope2);
    if (!(alpha > 0) || !std::isfinite(alpha))
        fail("the low-pass part below {} wavelengths has rms slope {}: no macro NDF", o.cutoff_wavelengths, alpha);
    return alpha;
}

// The mean-square slope of a macro NDF as wide as one ring of a measured map's periodogram (ring 0, |zeta| <= dzeta/2,
// at the split's reference wavenumber; docs/MODELS.md "Two-scale on a measured map"): the map tells no lobe narrower
// from a mirror. A facet of slope m moves zeta = k (i_xy + o_xy) by about 2 k m, and the uniform disc of radius
// dzeta/2 has mean |zeta|^2 = dzeta^2 / 8, so <|m|^2> = dzeta^2 / (32 k^2).
double two_scale_resolution_slope2(double dzeta) {
    const double k = kTwoPi / (kTwoScaleReferenceWavelength * 1e-3);
    return dzeta * dzeta / (32.0 * k * k);
}

// What two_scale takes from a measured map: the split against the band the map resolves, and the macro NDF's parts.
std::string two_scale_measured_note(const ModelOptions& o, const surface::MeasuredStatistics& s,
                                    const surface::PsdSplit& split, double waviness_slope2, double alpha) {
    const double zeta_c = split.zeta_c;
    std::string note = fmt::format(
        "two_scale on the measured map: split at zeta_c {:.4g} rad/um ({:.4g} wavelengths of {:.0f} nm, periods {:.4g} "
        "um) against the map's band {:.3g} .. {:.3g} rad/um; macro NDF alpha {:.4g} = the low-pass part's rms slope "
        "{:.3g}, the waviness's {:.3g} and the map's angular resolution {:.3g} (one ring of its periodogram, dzeta "
        "{:.3g} rad/um) in quadrature",
        zeta_c, o.cutoff_wavelengths, kTwoScaleReferenceWavelength, kTwoPi / zeta_c, s.first_ring(), s.nyquist(), alpha,
        std::sqrt(split.slope2_macro), std::sqrt(waviness_slope2),
        std::sqrt(two_scale_resolution_slope2(s.ring_width())), s.ring_width());
    if (s.first_ring() > zeta_c)
        note += fmt::format("; the map resolves no period longer than {:.4g} um (its first ring lies above zeta_c): the "
                            "macro NDF is its resolution{}, not measured slopes",
                            kTwoPi / zeta_c, waviness_slope2 > 0 ? " and the waviness" : "");
    if (!split.micro)
        note += fmt::format("; warning: the map resolves no roughness finer than {:.4g} um (its band ends at {:.3g} "
                            "rad/um, below zeta_c): the micro part is empty and the BRDF is the macro-facet model of "
                            "the map's slopes alone; roughness finer than its {:.3g} um pixels is not measured and would "
                            "add a diffraction lobe",
                            kTwoPi / zeta_c, s.nyquist(), kPi / s.nyquist());
    return note;
}

// two_scale on elliptical statistics (docs/MODELS.md "Two-scale on elliptical statistics"): the split on the ellipse
// inside the circle zeta_c (psd_split.hpp), per lay axis alpha = sqrt(2 <h_axis^2>) (ggx_stats' convention, so that
// LV = LU gives the isotropic alpha = rms slope of the low-pass part), the micro lobe the anisotropic GHS of the
// high-pass part.
std::unique_ptr<Bsdf> elliptical_two_scale(const ModelOptions& o, const surface::EllipticalStatistics& elliptical,
                                           double zeta_c, material::Conductor material, GhsSettings settings) {
    const auto split = surface::split_elliptical_psd(elliptical, zeta_c);
    const Vec2 alpha(macro_alpha(o, 2 * split.slope_variances_lay.x), macro_alpha(o, 2 * split.slope_variances_lay.y));
    auto micro = std::make_unique<AnisotropicGhsBsdf>(
        split.micro, std::make_shared<ExactScatterCore>(split.micro->radial_ptr()), material, std::move(settings));
    return std::make_unique<TwoScaleBsdf>(std::move(material), o.macro_ndf, alpha, elliptical.lay_angle(),
                                          std::move(micro));
}

GhsSettings ghs_settings(const ModelOptions& o) {
    GhsSettings settings;
    settings.fresnel = o.fresnel;
    settings.normalization = o.renormalization ? LobeNormalization::albedo : LobeNormalization::none;
    settings.relevant_roughness = o.renormalization;
    return settings;
}

// ggx_stats with psd measured 2d: the anisotropic GGX of the map's slope covariance (surface::slope_covariance, of the
// Gaussian-smoothed map for alpha_from smoothed), per principal axis the Beckmann convention of elliptical_ggx,
// alpha = sqrt(2 <h_axis^2>), u the axis of least slope; an isotropic map gives alpha_u ~ alpha_v ~ its rms slope.
std::unique_ptr<Bsdf> map_slope_ggx(const ModelOptions& o, SurfaceSource& surface, const material::Conductor& material,
                                    std::vector<std::string>* notes) {
    surface.measured(notes);  // the measured route's checks and notes, as for the other models
    const double smoothing = slope_smoothing(o);
    const surface::SlopeCovariance c =
        smoothing > 0 ? surface::slope_covariance(surface::gaussian_smooth(*surface.map(), smoothing, heightmap::Form::none),
                                                  heightmap::Form::none)
                      : surface::slope_covariance(*surface.map(), heightmap::Form::none);
    const auto axes = c.axes();
    const Vec2 alpha(checked_slope_alpha(o, smoothing, std::sqrt(2 * axes.along_u), "alpha_u"),
                     checked_slope_alpha(o, smoothing, std::sqrt(2 * axes.along_v), "alpha_v"));
    if (notes)
        notes->push_back(fmt::format("ggx_stats on the measured map's slope covariance: alpha_u {:.4g}, alpha_v {:.4g}, "
                                     "lay angle {:.4g} deg (measured_spectrum ring for the isotropic rms slope)",
                                     alpha.x, alpha.y, axes.angle_u / kDegree));
    return std::make_unique<GgxBsdf>(material, alpha, axes.angle_u);
}

// psd measured with measured_spectrum 2d (model_options.hpp): ghs (exact) and ghs_ssa on the map's 2-D periodogram
// (map_ghs.hpp); null for the models that keep what they took before (two_scale the ring average, ggx_stats the map's
// isotropic slope), saying so.
std::unique_ptr<Bsdf> map_spectrum_bsdf(const ModelOptions& o, SurfaceSource& surface, const material::Conductor& material,
                                        std::vector<std::string>* notes) {
    if (o.model == ModelKind::ggx && surface.map() &&
        (o.alpha_from == AlphaFrom::measured || o.alpha_from == AlphaFrom::smoothed))
        return map_slope_ggx(o, surface, material, notes);
    if (o.model == ModelKind::two_scale || o.model == ModelKind::ggx) {
        if (notes)
            notes->push_back(o.model == ModelKind::two_scale
                                 ? "two_scale takes the ring average of the measured PSD (measured_spectrum 2d applies "
                                   "to ghs, ghs_ssa and ggx_stats)"
                                 : "ggx_stats without the height map itself (measured statistics given) takes the "
                                   "isotropic rms slope of the ring average");
        return nullptr;
    }
    if (o.model != ModelKind::ghs && o.model != ModelKind::ghs_ssa) return nullptr;
    // A map's (make_bsdf takes a profile's radial statistics without this route).
    const auto& stats = static_cast<const surface::MapStatistics&>(surface.measured(notes));
    auto lobes = map_lobes(stats.spectrum());
    if (notes) {
        const double coverage = double(lobes->padding()) * stats.nyquist();
        notes->push_back(fmt::format(
            "measured 2-D spectrum: {} on the map's periodogram (not its ring average; measured_spectrum ring for that), "
            "sigma {:.6g} um over the whole lattice; self-convolutions on a {}-fold finer lattice, out to |zeta| = "
            "{:.3g} rad/um; largest share of a lobe in the outer quarter of that lattice {:.2g}{}; {}{}",
            to_string(o.model), lobes->sigma_h(), lobes->padding(), coverage, lobes->edge_fraction(),
            lobes->edge_fraction() > 1e-3 ? " (warning: the highest orders fold back there)" : "",
            lobes->clipped_fraction() > 0
                ? fmt::format("{}the masked periodogram's bins below zero ({:.2g} of its positive sum: its scatter where "
                              "the PSD lies below it{}) set to 0, each ring's sum kept; ",
                              lobes->clipped_fraction() > 0.1 ? "warning: " : "", lobes->clipped_fraction(),
                              lobes->clipped_fraction() > 0.1 ? ", which holds much of its high frequencies" : "")
                : std::string(),
            lobes->rough_rows() > 0
                ? fmt::format("g >= {:.4g} in the rough-surface limit (the Gaussian of the periodogram's slope "
                              "covariance; within {:.2g} of the lobe's peak there)",
                              lobes->rough_limit_g(), surface::SpectrumLobes2d::kRoughTolerance)
                : fmt::format("every g in full (the rough-surface limit would start at g = {:.4g})",
                              lobes->rough_limit_g())));
    }
    if (o.model == ModelKind::ghs_ssa)
        return std::make_unique<MapGhsBsdf>(std::move(lobes), o.ssa_form, material, ssa_settings(o.ssa_form, o.fresnel));
    return std::make_unique<MapGhsBsdf>(std::move(lobes), std::nullopt, material, ghs_settings(o));
}

// A profile where a map is expected (scenes, studies, Python; the CLI's brdf checks which options were given): its own
// spectrum as an isotropic surface's (psd measured); prepared by its form only.
void load_profile(SurfaceOptions& s, heightmap::LineScan scan) {
    const heightmap::Preparation& p = s.preparation;
    const heightmap::Preparation defaults;
    if (p.outliers != defaults.outliers || p.rows != defaults.rows || p.lambda_s_um != 0 || p.lambda_c_um)
        fail("{}: outliers, row_alignment, lambda_s and lambda_c apply to areal maps; a profile is prepared by its form "
             "only (form none | plane)", s.surface_file);
    if (p.form != heightmap::Form::none && p.form != heightmap::Form::plane)
        fail("{}: form {} on a profile: a profile's form is none (its mean) or plane (a least-squares line)",
             s.surface_file, heightmap::to_string(p.form));
    if (s.psd != PsdKind::measured)
        fail("psd {}: {} is a profile: its own spectrum is the surface (psd measured); the KC fitted to its 1-D PSD is "
             "the CLI's `brdf --psd file`", to_string(s.psd), s.surface_file);
    s.profile = std::make_shared<const heightmap::LineScan>(std::move(scan));
    s.measured_profile = std::make_shared<const surface::ProfileStatistics>(*s.profile, p.form);
}

}  // namespace

void load_height_map(SurfaceOptions& surface) {
    if (!(surface.psd == PsdKind::file || surface.psd == PsdKind::measured) || surface.measured_psd ||
        surface.measured_profile)
        return;
    if (surface.prepared) return;
    if (surface.height_map) {
        surface.prepared =
            std::make_shared<const heightmap::PreparedMap>(heightmap::prepare(*surface.height_map, surface.preparation));
    } else if (!surface.surface_file.empty()) {
        auto data = heightmap::read_surface_file(surface.surface_file, std::nullopt);
        if (auto* scan = std::get_if<heightmap::LineScan>(&data)) return load_profile(surface, std::move(*scan));
        surface.prepared = std::make_shared<const heightmap::PreparedMap>(
            heightmap::prepare(std::get<heightmap::HeightMap>(std::move(data)), surface.preparation));
    }
}

std::vector<std::string> preparation_notes(const SurfaceOptions& surface) {
    if (surface.profile) return {fmt::format("{}: {}", surface.surface_file,
                                             heightmap::describe_profile(*surface.profile, surface.preparation.form))};
    const heightmap::PreparedMap& p = *surface.prepared;
    const std::string name = surface.surface_file.empty() ? p.map.origin() : surface.surface_file;
    std::vector<std::string> notes{fmt::format("{}: {}", name, heightmap::describe(p))};
    if (p.outliers.count > 0)
        notes.push_back(heightmap::outliers_note(name, p.outliers, p.applied.outliers));
    return notes;
}

void validate(const ModelOptions& o) {
    if (o.model == ModelKind::ggx && o.alpha_from == AlphaFrom::none) require_microfacet_alpha(o.alpha, "alpha");
    if (o.alpha_from == AlphaFrom::smoothed) surface::require_surface_length(o.smoothing, "smoothing");
    if (o.truncation == Truncation::poisson_mass && !(o.epsilon > 0 && o.epsilon < 1))
        fail("epsilon must be in (0, 1), got {}", o.epsilon);
    if (o.model == ModelKind::two_scale && (!(o.cutoff_wavelengths > 0) || !std::isfinite(o.cutoff_wavelengths)))
        fail("cutoff_wavelengths must be > 0, got {}", o.cutoff_wavelengths);
    if (o.material.empty()) fail("material is empty: give a metal name, a file or 'perfect'");
    if (needs_surface(o)) validate_surface(o.surface);
    if (o.model == ModelKind::ghs && o.method == GhsMethod::refit &&
        (o.surface.psd == PsdKind::gaussian || o.surface.psd == PsdKind::measured))
        fail("method refit needs a K-correlation surface (psd kc, or file for the KC fitted to a height map), got psd {}",
             to_string(o.surface.psd));
}

std::unique_ptr<Bsdf> make_bsdf(const ModelOptions& o, std::vector<std::string>* notes) {
    validate(o);
    auto material = material::Conductor::from_name(o.material);
    SurfaceSource surface(needs_surface(o) ? o.surface : SurfaceOptions{});
    if (notes && (surface.options().prepared || surface.options().profile) && !surface.options().measured_psd &&
        !surface.options().preparation_noted)
        for (std::string& note : preparation_notes(surface.options())) notes->push_back(std::move(note));
    // The waviness's mean-square slope, once: the note below and two_scale's macro NDF take it.
    const double waviness_slope2 = needs_surface(o) ? surface.waviness_slope2() : 0.0;
    if (notes && needs_surface(o) && surface.options().prepared && surface.options().prepared->waviness) {
        const double slope = std::sqrt(waviness_slope2);
        const double lambda_c = surface.options().prepared->applied.lambda_c_um.value_or(0.0);
        notes->push_back(
            o.model == ModelKind::two_scale
                ? fmt::format("two_scale: the waviness (periods beyond lambda_c {:.4g} um, rms slope {:.3g}) is added "
                              "to the macro NDF's slopes", lambda_c, slope)
                : fmt::format("{}: the waviness (periods beyond lambda_c {:.4g} um, rms slope {:.3g}) is left out: the "
                              "BRDF is that of the band the map resolves below lambda_c; across the sample the "
                              "waviness tilts it by about +-{:.2g} deg (two_scale adds it to its macro slopes)",
                              to_string(o.model), lambda_c, slope, std::atan(slope) / kDegree));
    }
    // A profile's 2-D PSD is isotropic by assumption: every model reads it as radial statistics, exactly what the
    // 2-D route would read off a lattice of it.
    if (needs_surface(o) && o.surface.psd == PsdKind::measured && !surface.options().measured_profile &&
        o.surface.measured_spectrum == MeasuredSpectrum::two_d)
        if (auto bsdf = map_spectrum_bsdf(o, surface, material, notes)) return bsdf;
    // Elliptical statistics (null for an isotropic surface): the GHS family and two_scale's micro lobe take them
    // through AnisotropicGhsBsdf, ggx_stats and two_scale's macro NDF through the anisotropic microfacet NDFs.
    const auto elliptical = surface.elliptical(notes);
    if (elliptical && o.model == ModelKind::ggx) return elliptical_ggx(o, surface, *elliptical, std::move(material));
    switch (o.model) {
        case ModelKind::ggx: return std::make_unique<GgxBsdf>(std::move(material), ggx_alpha(o, surface, notes));
        case ModelKind::ghs_ssa:
            if (elliptical) return make_ghs_ssa(elliptical, std::move(material), o.ssa_form, o.fresnel);
            return make_ghs_ssa(surface.statistics(notes), std::move(material), o.ssa_form, o.fresnel);
        case ModelKind::ghs: {
            auto stats = surface.statistics(notes);
            std::shared_ptr<const ScatterCore> core;
            if (o.method == GhsMethod::exact) {
                core = std::make_shared<ExactScatterCore>(stats);
            } else {
                const surface::KCorrelation kc = surface.kc();
                const double x = surface::refit_self_convolutions(kc, kRefitOrders).exponent_x;
                core = std::make_shared<RefitScatterCore>(kc, x, o.truncation, o.epsilon);
            }
            if (elliptical)
                return std::make_unique<AnisotropicGhsBsdf>(elliptical, std::move(core), std::move(material),
                                                            ghs_settings(o));
            return std::make_unique<GhsBsdf>(std::move(stats), std::move(core), std::move(material), ghs_settings(o));
        }
        case ModelKind::two_scale: {
            const double zeta_c = surface::cutoff_frequency(kTwoScaleReferenceWavelength, o.cutoff_wavelengths);
            GhsSettings settings = ghs_settings(o);
            settings.name = "two_scale_micro";
            if (elliptical) return elliptical_two_scale(o, *elliptical, zeta_c, std::move(material), std::move(settings));
            const auto split = surface::split_psd(surface.statistics(notes), zeta_c, surface::LowPassFilter::sharp);
            // The rms slope of the low-pass part, and of the map's waviness (what its L-filter removed), which is
            // slope the macro NDF carries as well; of a measured map also its angular resolution (two_scale_resolution).
            const double resolution2 = o.surface.psd == PsdKind::measured
                                           ? two_scale_resolution_slope2(surface.measured(notes).ring_width())
                                           : 0.0;
            const double alpha = macro_alpha(o, split.slope2_macro + waviness_slope2 + resolution2);
            if (notes && o.surface.psd == PsdKind::measured)
                notes->push_back(two_scale_measured_note(o, surface.measured(notes), split, waviness_slope2, alpha));
            std::unique_ptr<Bsdf> micro;
            if (split.micro)
                micro = std::make_unique<GhsBsdf>(split.micro, std::make_shared<ExactScatterCore>(split.micro),
                                                  material, settings);
            return std::make_unique<TwoScaleBsdf>(std::move(material), o.macro_ndf, alpha, std::move(micro));
        }
    }
    fail("unknown model");
}

}  // namespace surfscatter::bsdf
